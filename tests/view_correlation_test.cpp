// The 1991 View Correlation method (calib/view_correlation.h).
#include <gtest/gtest.h>

#include <ceres/gradient_checker.h>

#include <random>

#include "calib/calibration.h"
#include "core/error.h"
#include "calib/f_test.h"
#include "calib/reprojection_cost.h"
#include "calib/view_correlation.h"
#include "calibration_fixture.h"
#include "test_util.h"

namespace insitu {
namespace {

using test::make_truth;
using test::Truth;

// Graphics Gems II's screen_project, written out from the original:
//   sx = −(d/s·halfx·x_v/z_v) + xcenter,  sy = −(aspect·d/s·halfx·y_v/z_v) + ycenter
// with (x_v, y_v, z_v) = (p − eye) in the frame z = normalize(eye − look), x = up × z, y = z × x.
Vec2d vc_screen_project(const ViewCorrelation& vc, const Vec3d& p) {
  const Vec3d z = (vc.eye - vc.look).normalized();
  const Vec3d x = vc.up.normalized().cross(z).normalized();
  const Vec3d y = z.cross(x).normalized();
  const Vec3d d = p - vc.eye;
  const double xv = d.dot(x), yv = d.dot(y), zv = d.dot(z);
  return {-(vc.d_over_s * vc.halfx * xv / zv) + vc.xcenter,
          -(vc.aspect * vc.d_over_s * vc.halfx * yv / zv) + vc.ycenter};
}

TEST(ViewCorrelation, ProjectionAgreesWithTheOriginalFormula) {
  std::mt19937 rng(20);
  const Truth t = make_truth(rng, 8, 50, false, 1.0, 720, 486, CameraModel::kFCA);
  const ViewCorrelation vc = view_correlation_from_camera(t.camera, t.clean);
  for (const auto& p : t.clean) {
    const Vec2d s = vc_screen_project(vc, p.p_world);
    // VC's screen y grows upward from the bottom edge.
    EXPECT_NEAR(s.x(), p.uv_px.x(), 1e-9);
    EXPECT_NEAR(s.y(), t.camera.height - p.uv_px.y(), 1e-9);
  }
}

TEST(ViewCorrelation, FileRoundTripAndCalibrationFromIt) {
  std::mt19937 rng(21);
  const Truth t = make_truth(rng, 9, 45, false, 1.0, 640, 480, CameraModel::kF);
  test::TempDir dir;
  write_view_correlation(dir.file("old.vc"), view_correlation_from_camera(t.camera, t.clean));
  const ViewCorrelation back = read_view_correlation(dir.file("old.vc"));
  const Camera cam = camera_from_view_correlation(back);
  EXPECT_NEAR(cam.fx, t.camera.fx, 1e-6);
  EXPECT_NEAR((cam.R_cam_from_world - t.camera.R_cam_from_world).norm(), 0, 1e-8);
  EXPECT_NEAR((cam.eye_world() - t.camera.eye_world()).norm(), 0, 1e-8);
  ASSERT_EQ(back.points.size(), t.clean.size());
  EXPECT_NEAR((back.points[3].uv_px - t.clean[3].uv_px).norm(), 0, 1e-6);
  // The points of a .vc file calibrate like any other.
  const auto pts = read_control_points(dir.file("old.vc"), false, 480);
  const CalibrationResult r = calibrate(pts, 640, 480);
  EXPECT_LT(std::abs(r.camera.fx / t.camera.fx - 1), 1e-6);
}

}  // namespace
}  // namespace insitu
