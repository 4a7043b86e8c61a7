#include <gtest/gtest.h>

#include <ceres/gradient_checker.h>

#include <random>

#include "calib/calibration.h"
#include "core/error.h"
#include "calib/f_test.h"
#include "calib/reprojection_cost.h"
#include "calib/view_correlation.h"
#include "test_util.h"

namespace insitu {
namespace {

// ---- Synthetic cameras and points ----------------------------------------------------------

struct Truth {
  Camera camera;
  std::vector<ControlPoint> clean;  // exact projections
};

// A camera `distance` away from a scene of size ~`scale` centred at `offset`, looking at it with a
// random tilt and roll, and n points seen by it: random pixels (5% margin) at random depths, or on
// a plane through the scene centre when coplanar.
Truth make_truth(std::mt19937& rng, int n, double hfov_deg, bool coplanar, double scale, int width, int height,
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

std::vector<ControlPoint> with_noise(const std::vector<ControlPoint>& pts, std::mt19937& rng, double sigma_px) {
  std::normal_distribution<double> g(0, sigma_px);
  auto out = pts;
  for (auto& p : out) p.uv_px += Vec2d(g(rng), g(rng));
  return out;
}

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
            EXPECT_LT((r.camera.eye_world() - t.camera.eye_world()).norm(), 1e-5 * scale / std::tan(deg_to_rad(fov) / 2));
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
            std::string::npos) << chosen;
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

// ---- The F-test against published tables ----------------------------------------------------

// Upper percentage points of the F distribution (e.g. NIST/SEMATECH e-Handbook, Table 1.3.6.7.2).
TEST(FTest, MatchesPublishedCriticalValues) {
  EXPECT_NEAR(f_distribution_sf(30.817, 2, 3), 0.01, 1e-4);
  EXPECT_NEAR(f_distribution_sf(4.965, 1, 10), 0.05, 1e-4);
  EXPECT_NEAR(f_distribution_sf(7.559, 2, 10), 0.01, 1e-4);
  EXPECT_NEAR(f_distribution_sf(3.098, 3, 20), 0.05, 1e-4);
  EXPECT_NEAR(f_distribution_sf(161.448, 1, 1), 0.05, 1e-4);
  EXPECT_DOUBLE_EQ(f_distribution_sf(0, 2, 5), 1.0);
  EXPECT_DOUBLE_EQ(f_distribution_sf(INFINITY, 2, 5), 0.0);
  // I_x(1, 1) = x; I_½(a, a) = ½.
  EXPECT_NEAR(regularized_incomplete_beta(1, 1, 0.3), 0.3, 1e-14);
  EXPECT_NEAR(regularized_incomplete_beta(7.5, 7.5, 0.5), 0.5, 1e-12);
}

// ---- View Correlation exchange ---------------------------------------------------------------

// Graphics Gems II's screen_project, written out from the original:
//   sx = −(d/s·halfx·x_v/z_v) + xcenter,  sy = −(aspect·d/s·halfx·y_v/z_v) + ycenter
// with (x_v, y_v, z_v) = (p − eye) in the frame z = normalize(eye − look), x = up × z, y = z × x.
Vec2d vc_screen_project(const ViewCorrelation& vc, const Vec3d& p) {
  const Vec3d z = (vc.eye - vc.look).normalized();
  const Vec3d x = vc.up.normalized().cross(z).normalized();
  const Vec3d y = z.cross(x).normalized();
  const Vec3d d = p - vc.eye;
  const double xv = d.dot(x), yv = d.dot(y), zv = d.dot(z);
  return {-(vc.d_over_s * vc.halfx * xv / zv) + vc.xcenter, -(vc.aspect * vc.d_over_s * vc.halfx * yv / zv) + vc.ycenter};
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

TEST(ControlPoints, JsonCsvAndErrors) {
  test::TempDir dir;
  dir.write("p.json", R"([{"uv": [1, 2], "xyz": [3, 4, 5], "name": "corner"}, {"uv": [6, 7], "xyz": [8, 9, 10]}])");
  const auto pj = read_control_points(dir.file("p.json"), false, 100);
  ASSERT_EQ(pj.size(), 2u);
  EXPECT_EQ(pj[0].name, "corner");
  EXPECT_EQ(pj[1].name, "#2");
  EXPECT_EQ(pj[1].p_world, Vec3d(8, 9, 10));
  dir.write("p.csv", "u,v,x,y,z,name\n1, 2, 3, 4, 5, a\n# comment\n6,7,8,9,10\n");
  const auto pc = read_control_points(dir.file("p.csv"), true, 100);  // bottom-left origin
  ASSERT_EQ(pc.size(), 2u);
  EXPECT_EQ(pc[0].uv_px, Vec2d(1, 98));
  EXPECT_EQ(pc[0].name, "a");
  dir.write("bad.csv", "1,2,3,4,5\n1,2,x,4,5\n");
  try {
    read_control_points(dir.file("bad.csv"), false, 100);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), dir.file("bad.csv") + ":2");
  }
  dir.write("bad.json", R"([{"uv": [1, 2], "xyz": [3, 4]}])");
  try {
    read_control_points(dir.file("bad.json"), false, 100);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), dir.file("bad.json") + ":$[0].xyz");
  }
}

}  // namespace
}  // namespace insitu
