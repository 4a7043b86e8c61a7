#include "core/output_paths.h"
#include "core/file_check.h"
#include "calib/control_points.h"

#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/json_reader.h"
#include "calib/view_correlation.h"

namespace insitu {
namespace fs = std::filesystem;

namespace {

std::vector<ControlPoint> read_json_list(const JsonValue& list) {
  std::vector<ControlPoint> points;
  for (std::size_t i = 0; i < list.size(); ++i) {
    JsonObject o(list.element(i));
    ControlPoint p;
    p.where = o.where();
    const JsonValue uv = o.get("uv");
    if (!uv.is_array() || uv.size() != 2) uv.fail("expected [u, v]");
    p.uv_px = {uv.element(0).number(), uv.element(1).number()};
    p.p_world = o.get("xyz").vec3();
    p.name = o.find("name") ? o.get("name").string() : fmt::format("#{}", i + 1);
    o.finish();
    points.push_back(p);
  }
  return points;
}

std::vector<ControlPoint> read_json_points(const std::string& path) {
  return control_points_from_json(read_json_file(path), path);
}

std::vector<ControlPoint> read_csv_points(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot read file");
  std::vector<ControlPoint> points;
  std::string line;
  for (int lineno = 1; std::getline(in, line); ++lineno) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::vector<std::string> fields;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');) {
      const auto b = f.find_first_not_of(" \t\r"), e = f.find_last_not_of(" \t\r");
      fields.push_back(b == std::string::npos ? "" : f.substr(b, e - b + 1));
    }
    if (fields.empty() || (fields.size() == 1 && fields[0].empty())) continue;
    const std::string where = fmt::format("{}:{}", path, lineno);
    double v[5];
    bool numeric = fields.size() >= 5;
    for (int k = 0; k < 5 && numeric; ++k) {
      char* end = nullptr;
      v[k] = std::strtod(fields[std::size_t(k)].c_str(), &end);
      numeric = end != fields[std::size_t(k)].c_str() && *end == '\0';
    }
    if (!numeric) {
      if (points.empty() && lineno == 1) continue;  // a header line
      throw InputError(where, "expected u, v, x, y, z[, name] (five numbers, then an optional name)");
    }
    for (double x : v)
      if (!std::isfinite(x)) throw InputError(where, "non-finite number");
    ControlPoint p;
    p.where = where;
    p.uv_px = {v[0], v[1]};
    p.p_world = {v[2], v[3], v[4]};
    p.name = fields.size() >= 6 && !fields[5].empty() ? fields[5] : fmt::format("#{}", points.size() + 1);
    points.push_back(p);
  }
  return points;
}

}  // namespace

std::vector<ControlPoint> control_points_from_json(const json& doc, const std::string& file) {
  const JsonValue root(doc, file, "$");
  if (!root.is_object()) return read_json_list(root);
  JsonObject wrapper(root);
  const JsonValue list = wrapper.get("points");
  wrapper.finish();
  return read_json_list(list);
}

std::optional<bool> parse_bottom_left_origin(const std::string& name) {
  if (name == "top_left" || name == "top-left") return false;
  if (name == "bottom_left" || name == "bottom-left") return true;
  return std::nullopt;
}

std::vector<ControlPoint> read_control_points(const std::string& path, bool bottom_left_origin, int image_height) {
  require_existing(path);
  const std::string ext = lower_extension(path);
  std::vector<ControlPoint> points;
  if (ext == ".json")
    points = read_json_points(path);
  else if (ext == ".csv" || ext == ".txt")
    points = read_csv_points(path);
  else if (ext == ".vc")
    return read_view_correlation(path).points;  // converted by the reader
  else
    throw InputError(path, "unknown control-point format '" + ext + "' (use .json, .csv or .vc)");
  if (bottom_left_origin)
    for (auto& p : points) p.uv_px.y() = image_height - p.uv_px.y();
  return points;
}

}  // namespace insitu
