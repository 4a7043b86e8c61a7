// The points panel's calibration: the library's calibration of the current points,
// as JSON for the page: the chosen model and its σ, each point's residual vector, the report the
// CLI prints, the uncertainty at each object with where to click next, and the local scene's
// grid and room box drawn through the camera.
#pragma once
#include <optional>
#include <vector>

#include "calib/calibration.h"
#include "core/json_reader.h"
#include "scene/spec.h"

namespace insitu {

// Throws InputError as calibrate() does (fewer than five points, degenerate points).
json calibration_view(const std::vector<ControlPoint>& points, int width, int height,
                      const std::optional<CameraModel>& model, const SceneSpec& scene);

}  // namespace insitu
