// The calibration's parameters in its normalized frames (Hartley's normalization), shared by the
// fit (calibration.cpp) and the questions asked of it afterwards (object_uncertainty.cpp).
// Internal to src/calib.
#pragma once
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "calib/calibration.h"
#include "core/camera.h"

namespace insitu::calib_detail {

struct Frames {
  Vec2d image_centre;  // (W/2, H/2)
  double image_scale;  // max(W, H)/2 pixels per normalized unit
  Vec3d world_centre;  // centroid of the points
  double world_scale;  // RMS distance of the points from it
  Vec2d to_norm(const Vec2d& uv) const { return (uv - image_centre) / image_scale; }
  Vec3d to_norm(const Vec3d& p) const { return (p - world_centre) / world_scale; }
};

// The parameters in normalized frames: p_cam = R(aa)·p_norm + t; intrinsics [f, cx, cy, a].
struct Params {
  double aa[3] = {0, 0, 0};
  double t[3] = {0, 0, 1};
  double intr[4] = {1, 0, 0, 1};
};

// The j-th of the ten parameters: aa (0–2), t (3–5), intr (6–9).
inline double& param(Params& p, int j) { return j < 3 ? p.aa[j] : j < 6 ? p.t[j - 3] : p.intr[j - 6]; }

// The Jacobian of g(params) (n values) by central differences, one column per parameter.
template <int N, typename G>
Eigen::Matrix<double, N, 10> numeric_jacobian(const Params& P, const G& g) {
  Eigen::Matrix<double, N, 10> J;
  for (int j = 0; j < 10; ++j) {
    Params plus = P, minus = P;
    const double h = 1e-6 * std::max(1.0, std::abs(param(plus, j)));
    param(plus, j) += h;
    param(minus, j) -= h;
    J.col(j) = (g(plus) - g(minus)) / (2 * h);
  }
  return J;
}

inline void constrain(Params& p, CameraModel model) {
  if (model == CameraModel::kF) {
    p.intr[1] = p.intr[2] = 0;
  }
  if (model != CameraModel::kFCA) p.intr[3] = 1;
}

inline Mat3d rotation_of(const Params& p) {
  const Vec3d aa(p.aa[0], p.aa[1], p.aa[2]);
  const double angle = aa.norm();
  return angle > 0 ? Eigen::AngleAxisd(angle, aa / angle).toRotationMatrix() : Mat3d::Identity();
}

inline void set_rotation(Params& p, const Mat3d& R) {
  const Eigen::AngleAxisd a(R);
  const Vec3d v = a.axis() * a.angle();
  for (int k = 0; k < 3; ++k) p.aa[k] = v[k];
}

// Back to pixels and world units: p_cam(world units) = s_w (R (p − c)/s_w + t) = R p + (s_w t − R c).
inline Camera to_camera(const Params& p, const Frames& fr, int width, int height) {
  Camera cam;
  cam.width = width;
  cam.height = height;
  cam.fx = p.intr[0] * fr.image_scale;
  cam.fy = p.intr[3] * p.intr[0] * fr.image_scale;
  cam.cx = fr.image_centre.x() + p.intr[1] * fr.image_scale;
  cam.cy = fr.image_centre.y() + p.intr[2] * fr.image_scale;
  cam.R_cam_from_world = rotation_of(p);
  cam.t_cam_from_world = fr.world_scale * Vec3d(p.t[0], p.t[1], p.t[2]) - cam.R_cam_from_world * fr.world_centre;
  return cam;
}

struct NormPoint {
  Vec2d uv;
  Vec3d p;
};

inline Vec2d project_norm(const Params& p, const Vec3d& x, double* depth = nullptr) {
  const Vec3d c = rotation_of(p) * x + Vec3d(p.t[0], p.t[1], p.t[2]);
  if (depth) *depth = c.z();
  return {p.intr[0] * c.x() / c.z() + p.intr[1], p.intr[3] * p.intr[0] * c.y() / c.z() + p.intr[2]};
}

inline double rss_norm(const Params& p, const std::vector<NormPoint>& pts) {
  double s = 0;
  for (const auto& q : pts) s += (project_norm(p, q.p) - q.uv).squaredNorm();
  return s;
}

}  // namespace insitu::calib_detail
