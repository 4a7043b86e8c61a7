#include <gtest/gtest.h>

#include <random>

#include "calib/calibration.h"
#include "calib/object_uncertainty.h"
#include "calibration_fixture.h"

namespace insitu {
namespace {

// A room photographed from a corner (issue 14): the camera near one corner of a 5 × 2.7 × 4 m room
// looks at the far corner; its principal point is 8–30 px off the centre of a 1200 × 900 photo.
// The clicks are landmarks on the two far walls in the right half of the photo; the furniture (a
// sofa-sized box) stands on the floor in the left half, nearer the camera.
struct CornerRoom {
  Camera truth;
  std::vector<ControlPoint> clicks;  // with noise
  Vec3d sofa_lo, sofa_hi;
};

CornerRoom corner_room(std::mt19937& rng, double noise_px) {
  std::uniform_real_distribution<double> u(0, 1);
  CornerRoom s;
  const Vec3d eye(0.3 + 0.3 * u(rng), 1.4 + 0.3 * u(rng), 3.4 + 0.4 * u(rng));
  const Vec3d look(3.0 + 0.6 * u(rng), 0.8 + 0.4 * u(rng), 0.1 + 0.5 * u(rng));
  s.truth = Camera::look_at(eye, look, Vec3d(0, 1, 0), 55 + 20 * u(rng), 1200, 900);
  const double off = 8 + 22 * u(rng), angle = 2 * M_PI * u(rng);
  s.truth.cx += off * std::cos(angle);
  s.truth.cy += off * std::sin(angle);
  std::normal_distribution<double> g(0, noise_px);
  for (int tries = 0; s.clicks.size() < 13 && tries < 10000; ++tries) {
    const bool back = s.clicks.size() % 2 == 0;  // the z = 0 wall, else the x = 5 wall: alternately
    const Vec3d p = back ? Vec3d(0.5 + 4.5 * u(rng), 2.7 * u(rng), 0) : Vec3d(5, 2.7 * u(rng), 4 * u(rng));
    double depth = 0;
    const Vec2d uv = s.truth.project(p, &depth);
    if (!(depth > 0) || uv.x() < 600 || uv.x() > 1190 || uv.y() < 10 || uv.y() > 890) continue;
    ControlPoint cp;
    cp.name = "w" + std::to_string(s.clicks.size());
    cp.p_world = p;
    cp.uv_px = uv + Vec2d(g(rng), g(rng));
    s.clicks.push_back(cp);
  }
  // The sofa: 2 × 0.85 × 0.9 m on the floor, where the photo's left half sees it.
  for (int tries = 0; tries < 1000; ++tries) {
    const Vec3d lo(0.8 + 2.0 * u(rng), 0, 0.6 + 2.0 * u(rng));
    double depth = 0;
    const Vec2d uv = s.truth.project(lo + Vec3d(1, 0.4, 0.45), &depth);
    s.sofa_lo = lo;
    s.sofa_hi = lo + Vec3d(2.0, 0.85, 0.9);
    if (depth > 0 && uv.x() > 60 && uv.x() < 600 && uv.y() > 60 && uv.y() < 840) break;
  }
  return s;
}

struct Coverage {
  int corners = 0, within_radius = 0, within_noise_radius = 0, objects_outside = 0;
};

Coverage simulate(int trials, unsigned seed) {
  std::mt19937 rng(seed);
  Coverage c;
  for (int t = 0; t < trials; ++t) {
    const CornerRoom s = corner_room(rng, 0.7);
    if (s.clicks.size() < 13) continue;
    const CalibrationResult r = calibrate(s.clicks, 1200, 900);
    const ObjectUncertainty o = object_uncertainty(r, "sofa", box_corners(s.sofa_lo, s.sofa_hi));
    c.objects_outside += !o.outside.empty();
    for (const PointUncertainty& p : o.points) {
      double depth = 0;
      const Vec2d truth_px = s.truth.project(p.point.p_world, &depth);
      if (!(depth > 0)) continue;
      const double error_px = (truth_px - p.uv_px).norm();
      ++c.corners;
      c.within_radius += error_px <= p.radius95_px;
      c.within_noise_radius += error_px <= p.noise_radius95_px;
    }
  }
  return c;
}

// The 95 % radius, with the model's own error, covers the true error at the sofa's corners in at
// least 90 % of cases; the radius from noise alone (the model assumed true) does not.
TEST(ObjectUncertainty, NinetyFivePercentRadiusCoversTheTrueErrorAtTheFurniture) {
  const int trials = 120;
  const Coverage c = simulate(trials, 1401);
  ASSERT_GT(c.corners, 8 * trials * 9 / 10);
  const double with_model = double(c.within_radius) / c.corners, noise_only = double(c.within_noise_radius) / c.corners;
  std::printf(
      "corners %d: covered by r95 %.1f %%, by the noise-only r95 %.1f %%; sofa outside the clicks' span in %d trials\n",
      c.corners, 100 * with_model, 100 * noise_only, c.objects_outside);
  EXPECT_GE(with_model, 0.90);
  EXPECT_LT(noise_only, 0.90);
  EXPECT_GT(c.objects_outside, trials * 9 / 10);  // the sofa is nearer than every click
}

// `calibrate --at` and `--box` print one figure at one point (issue 46: they disagreed by up to 3×).
// The insertion point's 95 % radius is the objects' (the model's own error included), and like it
// covers the true error in at least 90 % of rooms, where the noise alone does not.
TEST(ObjectUncertainty, TheInsertionPointGetsTheObjectsFigure) {
  std::mt19937 rng(4601);
  int trials = 0, within = 0, within_noise = 0;
  for (int t = 0; t < 120; ++t) {
    const CornerRoom s = corner_room(rng, 0.7);
    if (s.clicks.size() < 13) continue;
    CalibrationOptions options;
    options.insertion_world = s.sofa_lo;  // the sofa's nearest foot: outside the clicks' span
    const CalibrationResult r = calibrate(s.clicks, 1200, 900, options);
    const PointUncertainty at = object_uncertainty(r, "sofa", {{"foot", s.sofa_lo}}).points.at(0);
    EXPECT_DOUBLE_EQ(r.insertion_radius95_px, at.radius95_px);
    EXPECT_DOUBLE_EQ(r.insertion_noise_radius95_px, at.noise_radius95_px);
    const double error_px = (s.truth.project(s.sofa_lo) - r.insertion_px).norm();
    ++trials;
    within += error_px <= r.insertion_radius95_px;
    within_noise += error_px <= r.insertion_noise_radius95_px;
  }
  ASSERT_GT(trials, 100);
  std::printf("insertion point: covered by r95 in %d of %d rooms, by the noise alone in %d\n", within, trials,
              within_noise);
  EXPECT_GE(within, trials * 9 / 10);
  EXPECT_LT(within_noise, trials * 9 / 10);
}

// The worst true error at the sofa's corners under a calibration.
double worst_error_px(const CalibrationResult& r, const CornerRoom& s) {
  double worst = 0;
  for (const NamedPoint& p : box_corners(s.sofa_lo, s.sofa_hi))
    worst = std::max(worst, (r.camera.project(p.p_world) - s.truth.project(p.p_world)).norm());
  return worst;
}

// One more click where suggest_next_click says (the floor near the sofa) helps the sofa more than
// one more click where the user already clicked (another point on the far walls); and the hint
// predicts a smaller σ than before.
TEST(ObjectUncertainty, TheSuggestedClickHelpsMoreThanAnotherOnTheWalls) {
  std::mt19937 rng(1402);
  std::normal_distribution<double> g(0, 0.7);
  double sum_hint = 0, sum_wall = 0;
  int trials = 0;
  for (int t = 0; t < 40; ++t) {
    CornerRoom s = corner_room(rng, 0.7);
    if (s.clicks.size() < 13) continue;
    const CalibrationResult r = calibrate(s.clicks, 1200, 900);
    const std::vector<ObjectUncertainty> objects{object_uncertainty(r, "sofa", box_corners(s.sofa_lo, s.sofa_hi))};
    const std::optional<ClickHint> hint = suggest_next_click(r, objects);
    ASSERT_TRUE(hint.has_value());
    EXPECT_LT(hint->sigma_after_px, hint->sigma_before_px);
    EXPECT_NEAR(hint->p_world.y(), 0.0, 1e-9);
    auto with_click = [&](const Vec3d& p) {
      std::vector<ControlPoint> more = s.clicks;
      ControlPoint cp;
      cp.name = "next";
      cp.p_world = p;
      cp.uv_px = s.truth.project(p) + Vec2d(g(rng), g(rng));
      more.push_back(cp);
      return worst_error_px(calibrate(more, 1200, 900), s);
    };
    sum_hint += with_click(hint->p_world);
    // Another wall point among the clicks: half-way between two of them on the z = 0 wall.
    const Vec3d wall = 0.5 * (s.clicks[0].p_world + s.clicks[2].p_world);
    sum_wall += with_click(wall);
    ++trials;
  }
  ASSERT_GT(trials, 30);
  std::printf("mean worst error at the sofa: %.2f px after the suggested click, %.2f px after one more on the wall\n",
              sum_hint / trials, sum_wall / trials);
  EXPECT_LT(sum_hint, 0.5 * sum_wall);
}

}  // namespace
}  // namespace insitu
