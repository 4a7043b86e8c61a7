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
using test::with_noise;

// ---- Noise-free accuracy over the whole range --------------------------------------------------

TEST(Calibration, NoiseFreeIsExactAcrossTheRange) {
  std::mt19937 rng(11);
  const double fovs[] = {10, 30, 60, 90, 120};
  const int counts[] = {5, 6, 10, 100};
  const double scales[] = {1e-3, 1.0, 1e3};
  const std::pair<int, int> sizes[] = {{64, 48}, {640, 480}, {12000, 8000}};
  int cases = 0;
  for (double fov : fovs)
    for (int n : counts)
      for (bool coplanar : {false, true})
        for (double scale : scales)
          for (auto [w, h] : sizes) {
            // A third of the combinations, chosen by the seed, keeps the test quick.
            if (rng() % 3 != 0) continue;
            ++cases;
            const Truth t = make_truth(rng, n, fov, coplanar, scale, w, h, CameraModel::kF);
            const CalibrationResult r = calibrate(t.clean, w, h);
            SCOPED_TRACE(::testing::Message() << "fov " << fov << " n " << n << " coplanar " << coplanar << " scale "
                                              << scale << " size " << w << "x" << h);
            EXPECT_LT(r.rms_px, 1e-6);
            EXPECT_LT(std::abs(r.camera.fx / t.camera.fx - 1), 1e-6);
            EXPECT_EQ(r.model, CameraModel::kF);
            EXPECT_LT((r.camera.eye_world() - t.camera.eye_world()).norm(),
                      1e-5 * scale / std::tan(deg_to_rad(fov) / 2));
          }
  EXPECT_GT(cases, 60);
}

TEST(Calibration, NoiseFreeRicherModelsAreRecovered) {
  std::mt19937 rng(12);
  for (CameraModel model : {CameraModel::kFC, CameraModel::kFCA})
    for (int trial = 0; trial < 5; ++trial) {
      const Truth t = make_truth(rng, 12, 50, false, 1.0, 1600, 1200, model);
      const CalibrationResult r = calibrate(t.clean, 1600, 1200);
      EXPECT_EQ(r.model, model) << r.selection;
      EXPECT_LT(r.rms_px, 1e-6);
      EXPECT_NEAR(r.camera.cx, t.camera.cx, 1e-5);
      EXPECT_NEAR(r.camera.fy / r.camera.fx, t.camera.fy / t.camera.fx, 1e-8);
    }
}

// ---- Noise -------------------------------------------------------------------------------

// E[RSS] = σ²(m − k) for a linearized least-squares fit: the mean of RSS/(m − k) over many
// trials must match σ²; its standard error is σ²·sqrt(2/(m − k))/sqrt(trials) (≈1.8% here).
TEST(Calibration, ResidualsAreConsistentWithNoiseAndDegreesOfFreedom) {
  std::mt19937 rng(13);
  const int n = 20, trials = 150;
  for (double sigma : {0.5, 2.0}) {
    const Truth t = make_truth(rng, n, 60, false, 1.0, 1920, 1080, CameraModel::kF);
    CalibrationOptions opt;
    opt.model = CameraModel::kF;
    double mean_var = 0;
    for (int k = 0; k < trials; ++k) {
      const CalibrationResult r = calibrate(with_noise(t.clean, rng, sigma), 1920, 1080, opt);
      mean_var += r.sigma_px * r.sigma_px / trials;
    }
    EXPECT_NEAR(mean_var / (sigma * sigma), 1.0, 0.1) << "sigma " << sigma;
  }
}

// The reported standard deviations agree with the spread of the estimates over many trials.
TEST(Calibration, ReportedStandardDeviationsMatchObservedSpread) {
  std::mt19937 rng(14);
  for (CameraModel model : {CameraModel::kF, CameraModel::kFC}) {
    const Truth t = make_truth(rng, 15, 55, false, 1.0, 1600, 1200, model);
    CalibrationOptions opt;
    opt.model = model;
    const int trials = 200;
    std::vector<double> fx, eye_x, cx, ins_u;
    double rep_fx = 0, rep_eye = 0, rep_cx = 0;
    for (int k = 0; k < trials; ++k) {
      const CalibrationResult r = calibrate(with_noise(t.clean, rng, 1.0), 1600, 1200, opt);
      ASSERT_TRUE(r.sigma.known);
      fx.push_back(r.camera.fx);
      eye_x.push_back(r.camera.eye_world().x());
      cx.push_back(r.camera.cx);
      rep_fx += r.sigma.fx_px / trials;
      rep_eye += r.sigma.eye_world.x() / trials;
      rep_cx += r.sigma.cx_px / trials;
    }
    auto sd = [](const std::vector<double>& v) {
      double m = 0, s = 0;
      for (double x : v) m += x / double(v.size());
      for (double x : v) s += (x - m) * (x - m) / double(v.size() - 1);
      return std::sqrt(s);
    };
    SCOPED_TRACE(model_name(model));
    EXPECT_GT(rep_fx / sd(fx), 1 / 1.5);
    EXPECT_LT(rep_fx / sd(fx), 1.5);
    EXPECT_GT(rep_eye / sd(eye_x), 1 / 1.5);
    EXPECT_LT(rep_eye / sd(eye_x), 1.5);
    if (model == CameraModel::kFC) {
      EXPECT_GT(rep_cx / sd(cx), 1 / 1.5);
      EXPECT_LT(rep_cx / sd(cx), 1.5);
    }
  }
}

// Six noisy points from a camera with a centred principal point must not buy a free one.
TEST(Calibration, SixPointsDoNotBuyAFreePrincipalPoint) {
  std::mt19937 rng(15);
  int chose_f = 0;
  const int trials = 100;
  for (int k = 0; k < trials; ++k) {
    const Truth t = make_truth(rng, 6, 60, false, 1.0, 1600, 1200, CameraModel::kF);
    const CalibrationResult r = calibrate(with_noise(t.clean, rng, 1.0), 1600, 1200);
    chose_f += r.model == CameraModel::kF;
  }
  // α = 0.01 per test, two tests in the chain: at most ~2% false adoptions expected.
  EXPECT_GE(chose_f, 95);
}

// A parameter the chosen model does not fit is printed as fixed, with the reason, never as ± 0.
TEST(Calibration, ReportSaysWhichParametersAreFixedAndWhy) {
  std::mt19937 rng(17);
  const Truth t = make_truth(rng, 8, 60, false, 1.0, 640, 480, CameraModel::kF);
  const std::vector<ControlPoint> noisy = with_noise(t.clean, rng, 1.0);
  const std::string chosen = calibration_report(calibrate(noisy, 640, 480));
  EXPECT_NE(chosen.find("cx, cy       320.00 px, 240.00 px (the image centre: fixed, not supported by the points)"),
            std::string::npos)
      << chosen;
  EXPECT_NE(chosen.find("fy = fx (square pixels: fixed, not supported by the points)"), std::string::npos) << chosen;
  EXPECT_EQ(chosen.find("± 0.00"), std::string::npos) << chosen;
  CalibrationOptions fc;
  fc.model = CameraModel::kFC;
  const std::string requested = calibration_report(calibrate(noisy, 640, 480, fc));
  EXPECT_NE(requested.find("fy = fx (square pixels: fixed, by the requested model)"), std::string::npos) << requested;
  EXPECT_EQ(requested.find("(the image centre"), std::string::npos) << requested;
}

TEST(Calibration, OffCentrePrincipalPointIsDetectedWhenPointsSupportIt) {
  std::mt19937 rng(16);
  const Truth t = make_truth(rng, 40, 60, false, 1.0, 1600, 1200, CameraModel::kFC);
  const CalibrationResult r = calibrate(with_noise(t.clean, rng, 0.5), 1600, 1200);
  EXPECT_EQ(r.model, CameraModel::kFC) << r.selection;
}

TEST(Calibration, OutlierIsNamedAndTheCameraStaysRight) {
  std::mt19937 rng(17);
  for (double sigma : {0.0, 0.5, 2.0}) {
    const Truth t = make_truth(rng, 20, 60, false, 1.0, 1920, 1080, CameraModel::kF);
    auto pts = with_noise(t.clean, rng, sigma);
    pts[7].uv_px += Vec2d(30, -40);  // 50 px
    const CalibrationResult r = calibrate(pts, 1920, 1080);
    SCOPED_TRACE(calibration_report(r));
    EXPECT_TRUE(r.points[7].outlier) << "sigma " << sigma;
    for (std::size_t i = 0; i < pts.size(); ++i)
      if (i != 7) {
        EXPECT_FALSE(r.points[i].outlier) << r.points[i].name;
      }
    bool named = false;
    for (const auto& w : r.warnings.items) named |= w.find("p7") != std::string::npos;
    EXPECT_TRUE(named);
    EXPECT_EQ(r.inliers, 19);
    // The camera is right: within 4 reported standard deviations (or exact without noise).
    const double tol = sigma > 0 ? 4 * r.sigma.fx_px : 1e-6 * t.camera.fx;
    EXPECT_NEAR(r.camera.fx, t.camera.fx, tol) << "sigma " << sigma;
  }
}

// ---- Degenerate input ----------------------------------------------------------------------

TEST(Calibration, ErrorsAndWarnings) {
  std::mt19937 rng(18);
  const Truth t = make_truth(rng, 10, 60, false, 1.0, 800, 600, CameraModel::kF);
  // Fewer than five points.
  std::vector<ControlPoint> four(t.clean.begin(), t.clean.begin() + 4);
  EXPECT_THROW(calibrate(four, 800, 600), InputError);
  // Non-finite input.
  auto nan = t.clean;
  nan[2].p_world.x() = std::nan("");
  nan[2].where = "points.json:$[2]";
  try {
    calibrate(nan, 800, 600);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "points.json:$[2]");
  }
  // Collinear points.
  auto line = t.clean;
  for (std::size_t i = 0; i < line.size(); ++i) line[i].p_world = Vec3d(1, 2, 3) + double(i) * Vec3d(0.3, 0.1, -0.2);
  EXPECT_THROW(calibrate(line, 800, 600), InputError);
  // Duplicates warn.
  auto dup = t.clean;
  dup.push_back(dup[3]);
  dup.back().name = "again";
  const CalibrationResult rd = calibrate(dup, 800, 600);
  bool dup_warned = false;
  for (const auto& w : rd.warnings.items) dup_warned |= w.find("p3 and again") != std::string::npos;
  EXPECT_TRUE(dup_warned);
  // Coplanar points with a free principal point warn.
  const Truth flat = make_truth(rng, 10, 60, true, 1.0, 800, 600, CameraModel::kF);
  CalibrationOptions fc;
  fc.model = CameraModel::kFC;
  const CalibrationResult rc = calibrate(flat.clean, 800, 600, fc);
  EXPECT_TRUE(rc.coplanar);
  bool coplanar_warned = false;
  for (const auto& w : rc.warnings.items) coplanar_warned |= w.find("coplanar") != std::string::npos;
  EXPECT_TRUE(coplanar_warned);
  // Model too rich for the points.
  std::vector<ControlPoint> five(t.clean.begin(), t.clean.begin() + 5);
  CalibrationOptions fca;
  fca.model = CameraModel::kFCA;
  EXPECT_NO_THROW(calibrate(five, 800, 600, fca));  // 10 residuals, 10 parameters: exact
  // An implausible focal length warns.
  const Truth tele = make_truth(rng, 10, 0.5, false, 1.0, 800, 600, CameraModel::kF);
  const CalibrationResult rt = calibrate(tele.clean, 800, 600);
  bool fov_warned = false;
  for (const auto& w : rt.warnings.items) fov_warned |= w.find("implausible") != std::string::npos;
  EXPECT_TRUE(fov_warned);
}

TEST(Calibration, PointBehindTheCameraWarns) {
  std::mt19937 rng(19);
  Truth t = make_truth(rng, 12, 60, false, 1.0, 800, 600, CameraModel::kF);
  // A point behind the eye still has a "projection"; the true camera explains it exactly.
  ControlPoint back;
  back.p_world = t.camera.eye_world() - 2.0 * t.camera.forward_world() + 0.3 * t.camera.up_world();
  back.uv_px = t.camera.project(back.p_world);
  back.name = "behind_me";
  t.clean.push_back(back);
  const CalibrationResult r = calibrate(t.clean, 800, 600);
  bool warned = false;
  for (const auto& w : r.warnings.items) warned |= w.find("behind the camera: behind_me") != std::string::npos;
  EXPECT_TRUE(warned);
}

// ---- The cost functor ---------------------------------------------------------------------

TEST(Calibration, CostFunctorPassesGradientChecker) {
  std::unique_ptr<ceres::CostFunction> cost(ReprojectionCost::Create({0.1, -0.2}, {0.3, 0.4, -0.5}));
  ceres::NumericDiffOptions nd;
  const std::vector<const ceres::Manifold*>* no_manifolds = nullptr;
  ceres::GradientChecker checker(cost.get(), no_manifolds, nd);
  const double aa[3] = {0.1, -0.3, 0.2}, t[3] = {0.05, -0.1, 3.0}, intr[4] = {1.3, 0.02, -0.03, 1.05};
  const double* params[3] = {aa, t, intr};
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(params, 1e-7, &results)) << results.error_log;
}

}  // namespace
}  // namespace insitu
