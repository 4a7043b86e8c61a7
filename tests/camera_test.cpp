#include <gtest/gtest.h>

#include <random>

#include "core/camera.h"

namespace insitu {
namespace {

// A random rotation from a random unit quaternion.
Mat3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0, 1);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

TEST(Camera, ProjectUnprojectRoundTrip) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    Camera cam;
    cam.width = 1000 + int(500 * (u(rng) + 1));
    cam.height = 800;
    cam.fx = 300 + 1000 * (u(rng) + 1);
    cam.fy = cam.fx * (1 + 0.1 * u(rng));
    cam.cx = cam.width * (0.5 + 0.1 * u(rng));
    cam.cy = cam.height * (0.5 + 0.1 * u(rng));
    cam.R_cam_from_world = random_rotation(rng);
    cam.t_cam_from_world = Vec3d(u(rng), u(rng), u(rng)) * 10;
    for (int k = 0; k < 20; ++k) {
      const Vec2d uv(cam.width * (u(rng) + 1) / 2, cam.height * (u(rng) + 1) / 2);
      const double depth = 0.1 + 100 * (u(rng) + 1);
      const Vec3d p = cam.unproject(uv, depth);
      double z = 0;
      const Vec2d back = cam.project(p, &z);
      EXPECT_NEAR(z, depth, 1e-9 * depth);
      EXPECT_NEAR((back - uv).norm(), 0.0, 1e-8);
      // The primary ray through uv passes through p.
      const Ray ray = cam.ray(uv);
      const Vec3d to_p = (p - ray.origin.cast<double>());
      EXPECT_NEAR(to_p.normalized().dot(ray.dir.cast<double>()), 1.0, 1e-6);
    }
  }
}

// Hand-derived: a camera at the origin looking down −Z with up +Y has R = diag(1, −1, −1)
// (x right = +X, y down = −Y, z forward = −Z). hfov 90° on a 200-wide image: fx = 100.
TEST(Camera, LookAtByHand) {
  const Camera cam = Camera::look_at({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90.0, 200, 100);
  EXPECT_NEAR(cam.fx, 100.0, 1e-12);
  EXPECT_NEAR(cam.fy, 100.0, 1e-12);
  EXPECT_TRUE(cam.R_cam_from_world.isApprox(Vec3d(1, -1, -1).asDiagonal().toDenseMatrix(), 1e-12));
  // The point (1, 0.5, −2): X_c = (1, −0.5, 2), u = 100·1/2 + 100 = 150, v = 100·(−0.5)/2 + 50 = 25.
  const Vec2d uv = cam.project({1, 0.5, -2});
  EXPECT_NEAR(uv.x(), 150.0, 1e-12);
  EXPECT_NEAR(uv.y(), 25.0, 1e-12);
  // The image centre is on the axis; the top-left corner (0,0) looks at (−1, +0.5, −1)/|.|.
  EXPECT_TRUE(cam.ray({100, 50}).dir.isApprox(Vec3f(0, 0, -1), 1e-6f));
  EXPECT_TRUE(cam.ray({0, 0}).dir.isApprox(Vec3f(-1, 0.5f, -1).normalized(), 1e-6f));
  EXPECT_NEAR(cam.hfov_deg(), 90.0, 1e-9);
  // vfov = 2 atan(50/100).
  EXPECT_NEAR(cam.vfov_deg(), 2 * rad_to_deg(std::atan(0.5)), 1e-9);
}

// Eye at (0, 0, 5) looking at the origin; the camera translation is t = −R·eye = (0, 0, 5)
// because R maps world −Z to camera +Z: R·(0,0,5) = (0,0,−5).
TEST(Camera, TranslationByHand) {
  const Camera cam = Camera::look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 60.0, 640, 480);
  EXPECT_TRUE(cam.t_cam_from_world.isApprox(Vec3d(0, 0, 5), 1e-12));
  EXPECT_TRUE(cam.eye_world().isApprox(Vec3d(0, 0, 5), 1e-12));
  double z = 0;
  const Vec2d uv = cam.project({0, 0, 0}, &z);
  EXPECT_NEAR(z, 5.0, 1e-12);
  EXPECT_NEAR(uv.x(), 320.0, 1e-9);
  EXPECT_NEAR(uv.y(), 240.0, 1e-9);
  // A point above the origin projects above the centre (smaller v): y is down.
  EXPECT_LT(cam.project({0, 1, 0}).y(), 240.0);
  // A point at +X projects right of the centre.
  EXPECT_GT(cam.project({1, 0, 0}).x(), 320.0);
}

TEST(Camera, BehindTheCameraHasNegativeDepth) {
  const Camera cam = Camera::look_at({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60.0, 64, 48);
  double z = 0;
  cam.project({0, 0, 3}, &z);
  EXPECT_LT(z, 0.0);
}

TEST(Camera, ExtremeScales) {
  // Millimetres and kilometres: the round trip is relative to the scale.
  for (double scale : {1e-3, 1.0, 1e3}) {
    const Camera cam = Camera::look_at(Vec3d(1, 2, 3) * scale, Vec3d(0, 0, 0), {0, 1, 0}, 40.0, 4000, 3000);
    const Vec3d p = cam.unproject({1234.5, 987.25}, 2.0 * scale);
    const Vec2d uv = cam.project(p);
    EXPECT_NEAR(uv.x(), 1234.5, 1e-7);
    EXPECT_NEAR(uv.y(), 987.25, 1e-7);
  }
}

}  // namespace
}  // namespace insitu
