// Synthetic cameras and the exact projections of random points through them, for the
// calibration's tests.
#pragma once
#include <random>
#include <string>
#include <vector>

#include "calib/calibration.h"
#include "core/camera.h"

namespace insitu::test {

struct Truth {
  Camera camera;
  std::vector<ControlPoint> clean;  // exact projections
};

// A camera `distance` away from a scene of size ~`scale` centred at `offset`, looking at it with a
// random tilt and roll, and n points seen by it: random pixels (5% margin) at random depths, or on
// a plane through the scene centre when coplanar.
inline Truth make_truth(std::mt19937& rng, int n, double hfov_deg, bool coplanar, double scale, int width, int height,
                        CameraModel model) {
  std::uniform_real_distribution<double> u(-1, 1);
  const Vec3d offset = Vec3d(3, 0.5, -2) * scale;
  // Distance so that the scene of size `scale` roughly fills the field of view.
  const double distance = scale / std::tan(0.5 * deg_to_rad(hfov_deg));
  const Vec3d dir = Vec3d(u(rng), 0.3 * u(rng) - 0.3, u(rng)).normalized();
  const Vec3d eye = offset - distance * dir;
  const Vec3d up = (Vec3d(0, 1, 0) + 0.2 * Vec3d(u(rng), 0, u(rng))).normalized();
  Truth t;
  t.camera = Camera::look_at(eye, offset + 0.05 * scale * Vec3d(u(rng), u(rng), u(rng)), up, hfov_deg, width, height);
  if (model != CameraModel::kF) {
    t.camera.cx += 0.06 * width * u(rng);
    t.camera.cy += 0.06 * height * u(rng);
  }
  if (model == CameraModel::kFCA) t.camera.fy *= 1.08;
  const Vec3d plane_n = (-dir + 0.5 * Vec3d(u(rng), u(rng), u(rng))).normalized();
  for (int i = 0; i < n; ++i) {
    const Vec2d uv(width * (0.5 + 0.45 * u(rng)), height * (0.5 + 0.45 * u(rng)));
    Vec3d p;
    if (coplanar) {
      // The ray through uv meets the plane through `offset` with normal plane_n.
      const Vec3d o = t.camera.eye_world(), d = t.camera.unproject(uv, 1.0) - o;
      p = o + d * ((offset - o).dot(plane_n) / d.dot(plane_n));
    } else {
      p = t.camera.unproject(uv, distance * (1 + 0.5 * u(rng)));
    }
    ControlPoint cp;
    cp.p_world = p;
    cp.uv_px = t.camera.project(p);
    cp.name = "p" + std::to_string(i);
    t.clean.push_back(cp);
  }
  return t;
}

inline std::vector<ControlPoint> with_noise(const std::vector<ControlPoint>& pts, std::mt19937& rng, double sigma_px) {
  std::normal_distribution<double> g(0, sigma_px);
  auto out = pts;
  for (auto& p : out) p.uv_px += Vec2d(g(rng), g(rng));
  return out;
}

}  // namespace insitu::test
