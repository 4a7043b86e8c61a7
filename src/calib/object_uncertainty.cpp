#include "calib/object_uncertainty.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "calib/fit_state.h"

namespace insitu {

using namespace calib_detail;

namespace {

constexpr double kChi2_2_95 = 5.991;  // χ²₂(0.95)

// π(x) in pixels under the normalized parameters q.
Vec2d project_px(const Params& q, const Frames& fr, const Vec3d& p_world) {
  return fr.image_centre + fr.image_scale * project_norm(q, fr.to_norm(p_world));
}

// d π(x) / d θ, pixels per normalized parameter.
Eigen::Matrix<double, 2, 10> projection_jacobian_px(const ModelCovariance& m, const Frames& fr, const Vec3d& p_world) {
  return numeric_jacobian<2>(m.params, [&](const Params& q) { return project_px(q, fr, p_world); });
}

double major_variance(const Eigen::Matrix2d& S) {
  return std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(S).eigenvalues().maxCoeff());
}

double radius95(const ModelCovariance& m, const Frames& fr, const Vec3d& p_world) {
  const auto J = projection_jacobian_px(m, fr, p_world);
  return std::sqrt(kChi2_2_95 * major_variance(J * m.C * J.transpose()));
}

// Whether the clicks' convex hull in the image and their depth range contain the point.
bool outside_clicks(const CalibrationFitState& st, const Vec2d& uv_px, double depth) {
  if (!(depth >= st.click_depth_min && depth <= st.click_depth_max) || st.clicks_hull_px.empty()) return true;
  std::vector<cv::Point2f> hull;
  for (const Vec2d& p : st.clicks_hull_px) hull.emplace_back(float(p.x()), float(p.y()));
  return cv::pointPolygonTest(hull, cv::Point2f(float(uv_px.x()), float(uv_px.y())), false) < 0;
}

PointUncertainty point_uncertainty(const CalibrationResult& r, const NamedPoint& p) {
  const CalibrationFitState& st = *r.state;
  PointUncertainty u;
  u.point = p;
  double depth = 0;
  u.uv_px = r.camera.project(p.p_world, &depth);
  u.outside_clicks = outside_clicks(st, u.uv_px, depth);
  if (!st.chosen) {
    u.noise_sigma_px = u.noise_radius95_px = u.radius95_px = std::numeric_limits<double>::infinity();
    return u;
  }
  u.noise_radius95_px = radius95(*st.chosen, st.frames, p.p_world);
  u.noise_sigma_px = u.noise_radius95_px / std::sqrt(kChi2_2_95);
  u.radius95_px = u.noise_radius95_px;
  if (st.richer) {
    u.model_shift_px = (project_px(st.richer->params, st.frames, p.p_world) - u.uv_px).norm();
    u.radius95_px = std::max(u.radius95_px, u.model_shift_px + radius95(*st.richer, st.frames, p.p_world));
  } else if (int(r.model) < 2) {
    u.radius95_px = std::numeric_limits<double>::infinity();
  }
  return u;
}

}  // namespace

std::vector<NamedPoint> box_corners(const Vec3d& lo, const Vec3d& hi) {
  std::vector<NamedPoint> out;
  for (int iy = 0; iy < 2; ++iy)
    for (int ix = 0; ix < 2; ++ix)
      for (int iz = 0; iz < 2; ++iz)
        out.push_back({fmt::format("{} {}x{}z", iy ? "top" : "feet", ix ? '+' : '-', iz ? '+' : '-'),
                       Vec3d(ix ? hi.x() : lo.x(), iy ? hi.y() : lo.y(), iz ? hi.z() : lo.z())});
  return out;
}

ObjectUncertainty object_uncertainty(const CalibrationResult& r, const std::string& name,
                                     const std::vector<NamedPoint>& points) {
  if (!r.state) throw std::logic_error("object_uncertainty: the calibration has no fit state");
  const CalibrationFitState& st = *r.state;
  ObjectUncertainty o;
  o.name = name;
  int outside = 0;
  for (const NamedPoint& p : points) {
    o.points.push_back(point_uncertainty(r, p));
    outside += o.points.back().outside_clicks;
    if (o.points.back().radius95_px > o.points[o.worst].radius95_px) o.worst = o.points.size() - 1;
  }
  o.model_note = st.richer          ? fmt::format("against {}", model_name(st.richer->model))
                 : int(r.model) < 2 ? "the model's own error is not bounded: " + st.richer_note
                                    : st.richer_note;
  if (outside > 0)
    o.outside = fmt::format(
        "{} of its {} corners lie outside the clicked points' span (the convex hull of their pixels, "
        "or their range of depths)",
        outside, points.size());
  return o;
}

}  // namespace insitu
