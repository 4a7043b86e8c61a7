// insitu.h: cameras, calibration from points in memory, and the scene's camera.
#include <fmt/format.h>

#include "api/api_internal.h"
#include "interop/blender_camera.h"
#include "calib/calibration_summary.h"
#include "calib/view_correlation.h"
#include "core/json_reader.h"
#include "core/output_paths.h"

using namespace insitu;
using insitu::api::ApiMisuse;
using insitu::api::guarded;
using insitu::api::not_null;
using insitu::api::require;

namespace {

std::vector<ControlPoint> control_points(const insitu_control_point* p, std::size_t n) {
  if (n > 0) not_null(p, "the points");
  std::vector<ControlPoint> out;
  for (std::size_t i = 0; i < n; ++i)
    out.push_back({Vec2d(p[i].u_px, p[i].v_px), Vec3d(p[i].x_m, p[i].y_m, p[i].z_m), fmt::format("#{}", i + 1),
                   fmt::format("points[{}]", i)});
  return out;
}

std::optional<std::string> model_name_or_auto(const char* model) {
  if (!model || std::string(model) == "auto") return std::nullopt;
  if (!parse_model(model))
    throw InputError("model", fmt::format("'{}': expected \"auto\", \"f\", \"f+c\" or \"f+c+a\"", model));
  return std::string(model);
}

void fill(const Camera& c, insitu_camera& out) {
  out.width = c.width;
  out.height = c.height;
  out.fx = c.fx;
  out.fy = c.fy;
  out.cx = c.cx;
  out.cy = c.cy;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) out.R_cam_from_world[3 * r + k] = c.R_cam_from_world(r, k);
    out.t_cam_from_world[r] = c.t_cam_from_world[r];
  }
}

void summarize(insitu_calibration& c) {
  const CalibrationSummary s = summarize_calibration(c.result, c.boxes);
  c.report = s.report;
  c.json = json_text(s.camera_json, 2) + "\n";
}

}  // namespace

extern "C" {

insitu_status insitu_calibrate(const insitu_control_point* points, size_t n, int width, int height, const char* model,
                               const double* at_world, insitu_calibration** out) {
  return guarded([&] {
    require(out, "the calibration pointer");
    *out = nullptr;
    if (width < 1 || height < 1 || width > (1 << 20) || height > (1 << 20))
      throw InputError("size", fmt::format("{}x{}: expected 1 to 2^20 pixels each way", width, height));
    CalibrationOptions options;
    if (const auto m = model_name_or_auto(model)) options.model = parse_model(*m);
    if (at_world) options.insertion_world = Vec3d(at_world[0], at_world[1], at_world[2]);
    auto c = std::make_unique<insitu_calibration>();
    c->points = control_points(points, n);
    c->result = calibrate(c->points, width, height, options);
    summarize(*c);
    *out = c.release();
  });
}

void insitu_calibration_free(insitu_calibration* calibration) { delete calibration; }

insitu_status insitu_calibration_camera(const insitu_calibration* calibration, insitu_camera* camera) {
  return guarded([&] { fill(require(calibration, "the calibration").result.camera, require(camera, "the camera")); });
}

double insitu_calibration_rms_px(const insitu_calibration* calibration) {
  return calibration ? calibration->result.rms_px : -1.0;
}
const char* insitu_calibration_report(const insitu_calibration* calibration) {
  return calibration ? calibration->report.c_str() : "";
}
const char* insitu_calibration_json(const insitu_calibration* calibration) {
  return calibration ? calibration->json.c_str() : "";
}

const char* insitu_calibration_blender_script(insitu_calibration* calibration, const char* photo_path) {
  if (!calibration) return "";
  calibration->blender = blender_camera_script(calibration->result.camera, photo_path ? photo_path : "");
  return calibration->blender.c_str();
}

insitu_status insitu_calibration_write_vc(const insitu_calibration* calibration, const char* path) {
  return guarded([&] {
    const insitu_calibration& c = require(calibration, "the calibration");
    const std::string p = not_null(path, "the path");
    if (lower_extension(p) != ".vc") throw InputError(p, "a View Correlation file ends in .vc");
    std::vector<ControlPoint> inliers;
    for (std::size_t i = 0; i < c.points.size(); ++i)
      if (!c.result.points[i].outlier) inliers.push_back(c.points[i]);
    write_view_correlation(p, view_correlation_from_camera(c.result.camera, inliers));
  });
}

insitu_status insitu_calibration_add_box(insitu_calibration* calibration, const char* name, const double lo_world[3],
                                         const double hi_world[3]) {
  return guarded([&] {
    insitu_calibration& c = require(calibration, "the calibration");
    const std::string n = not_null(name, "the box's name");
    const Vec3d lo(not_null(lo_world, "lo_world")[0], lo_world[1], lo_world[2]);
    const Vec3d hi(not_null(hi_world, "hi_world")[0], hi_world[1], hi_world[2]);
    if (!lo.allFinite() || !hi.allFinite() || (lo.array() > hi.array()).any())
      throw InputError("box " + n, "expected finite corners with each minimum at most its maximum");
    c.boxes.emplace_back(n, box_corners(lo, hi));
    summarize(c);
  });
}

insitu_status insitu_scene_set_camera(insitu_scene* scene, const insitu_camera* camera) {
  return guarded([&] {
    insitu_scene& s = require(scene, "the scene");
    const insitu_camera& c = require(camera, "the camera");
    json R = json::array();
    for (int r = 0; r < 3; ++r)
      R.push_back({c.R_cam_from_world[3 * r], c.R_cam_from_world[3 * r + 1], c.R_cam_from_world[3 * r + 2]});
    json doc = s.doc;
    doc["camera"] = {
        {"intrinsics", {{"fx", c.fx}, {"fy", c.fy}, {"cx", c.cx}, {"cy", c.cy}}},
        {"pose", {{"R", R}, {"t", {c.t_cam_from_world[0], c.t_cam_from_world[1], c.t_cam_from_world[2]}}}}};
    auto points = std::move(s.points);
    s.points.reset();
    try {
      insitu::api::reparse(s, std::move(doc));
    } catch (...) {
      s.points = std::move(points);
      throw;
    }
    s.camera_size = std::pair{c.width, c.height};
  });
}

insitu_status insitu_scene_set_control_points(insitu_scene* scene, const insitu_control_point* points, size_t n,
                                              const char* model) {
  return guarded([&] {
    insitu_scene& s = require(scene, "the scene");
    auto old_points = std::move(s.points);
    auto old_model = std::move(s.points_model);
    std::vector<PointSpec> list;
    for (const ControlPoint& p : control_points(points, n)) list.push_back({p.uv_px, p.p_world});
    s.points = list;
    try {
      s.points_model = model_name_or_auto(model);
      insitu::api::reparse(s, s.doc);
    } catch (...) {
      s.points = std::move(old_points);
      s.points_model = std::move(old_model);
      throw;
    }
    s.camera_size.reset();
  });
}

insitu_status insitu_scene_camera(insitu_scene* scene, insitu_camera* camera) {
  return guarded([&] { fill(insitu::api::loaded(require(scene, "the scene")).camera, require(camera, "the camera")); });
}

insitu_status insitu_scene_calibration_report(insitu_scene* scene, const char** report) {
  return guarded([&] {
    insitu_scene& s = require(scene, "the scene");
    insitu::api::loaded(s);
    require(report, "the report pointer") = s.calibration_text.c_str();
  });
}

insitu_status insitu_scene_warnings(insitu_scene* scene, const char** warnings) {
  return guarded([&] {
    insitu_scene& s = require(scene, "the scene");
    insitu::api::loaded(s);
    require(warnings, "the warnings pointer") = s.warnings_text.c_str();
  });
}

}  // extern "C"
