#include "studio/calibration_view.h"

#include <filesystem>

#include "calib/calibration_summary.h"
#include "studio/overlay_lines.h"

namespace insitu {

namespace {

// Each object's uncertainty is asked at its origin (its feet, for a mesh modelled standing on
// y = 0): the page needs no mesh loaded to show where the furniture stands.
std::vector<NamedBox> object_origins(const SceneSpec& scene) {
  std::vector<NamedBox> boxes;
  for (const ObjectSpec& o : scene.objects)
    boxes.emplace_back(std::filesystem::path(o.mesh).filename().string(),
                       std::vector<NamedPoint>{{"origin", o.M_world_from_object.block<3, 1>(0, 3)}});
  return boxes;
}

// The grid of each local-scene plane, and the room box: the box spans the grid when there is one,
// else the control points do.
std::vector<std::pair<std::string, Segment3>> scene_lines(const SceneSpec& scene,
                                                          const std::vector<ControlPoint>& points) {
  Vec3d lo = Vec3d::Constant(HUGE_VAL), hi = -lo;
  for (const ControlPoint& p : points) lo = lo.cwiseMin(p.p_world), hi = hi.cwiseMax(p.p_world);
  const auto& box = scene.environment.room_box;
  if (box) lo = box->min, hi = box->max;
  std::vector<std::pair<std::string, Segment3>> lines;
  const double half = std::max(0.5 * (hi - lo).maxCoeff(), 1e-9);
  for (const PlaneSpec& plane : scene.local_scene)
    if (!plane.mesh)
      for (const Segment3& s : plane_grid(plane.point, plane.normal, 0.5 * (lo + hi), half))
        lines.emplace_back("grid", s);
  if (box)
    for (const Segment3& s : box_edges(box->min, box->max)) lines.emplace_back("box", s);
  return lines;
}

json points_json(const CalibrationResult& r) {
  json out = json::array();
  for (const PointResidual& p : r.points)
    out.push_back({{"name", p.name},
                   {"uv", {p.uv_px.x(), p.uv_px.y()}},
                   {"residual", {p.residual_px.x(), p.residual_px.y()}},
                   {"outlier", p.outlier},
                   {"behind", p.behind}});
  return out;
}

}  // namespace

json calibration_view(const std::vector<ControlPoint>& points, int width, int height,
                      const std::optional<CameraModel>& model, const SceneSpec& scene) {
  CalibrationOptions options;
  options.model = model;
  const CalibrationResult r = calibrate(points, width, height, options);
  const CalibrationSummary summary = summarize_calibration(r, object_origins(scene));
  json lines = json::array();
  for (const auto& [kind, s] : scene_lines(scene, points))
    if (const auto seg = project_segment(r.camera, s))
      lines.push_back({{"kind", kind}, {"a", {seg->a_px.x(), seg->a_px.y()}}, {"b", {seg->b_px.x(), seg->b_px.y()}}});
  const json& calibration = summary.camera_json.at("calibration");
  return {{"model", model_name(r.model)},
          {"selection", r.selection},
          {"sigma_px", r.sigma_px},
          {"rms_px", r.rms_px},
          {"inliers", r.inliers},
          {"points", points_json(r)},
          {"lines", lines},
          {"at_objects", calibration.contains("at_objects") ? calibration.at("at_objects") : json()},
          {"warnings", r.warnings.items},
          {"report", summary.report},
          {"camera", summary.camera_json}};
}

}  // namespace insitu
