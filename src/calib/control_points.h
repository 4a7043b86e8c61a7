// Control points: pixels clicked in the photo with their 3D world positions.
//
// points.json: a list of {"uv": [u, v], "xyz": [x, y, z], "name": "..."} (name optional), or an
// object {"points": [...]}. CSV: one point per line, `u, v, x, y, z[, name]`, '#' comments, an
// optional header line. View Correlation files (.vc) are read by view_correlation.h.
// With bottom_left_origin, v is measured up from the bottom edge (as in View Correlation files)
// and converted: v_top_left = height − v.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "core/json_reader.h"
#include "core/math.h"

namespace insitu {

struct ControlPoint {
  Vec2d uv_px = Vec2d::Zero();    // pixel position, top-left origin
  Vec3d p_world = Vec3d::Zero();  // metres
  std::string name;               // "#3" when unnamed (1-based)
  std::string where;              // file and place, for messages
};

// The pixel origin of the points, spelt as in the scene file ("top_left", "bottom_left") or as on
// the command line ("top-left", "bottom-left"): true for bottom-left, nullopt if neither.
std::optional<bool> parse_bottom_left_origin(const std::string& name);
constexpr const char* kOriginNames = "\"top_left\" or \"bottom_left\" (top-left, bottom-left also accepted)";

// The points of a points.json document already parsed; `file` names it in messages
// ("points.json:$[2].xyz: ..."). Top-left origin.
std::vector<ControlPoint> control_points_from_json(const json& doc, const std::string& file);

std::vector<ControlPoint> read_control_points(const std::string& path, bool bottom_left_origin, int image_height);

}  // namespace insitu
