#include <gtest/gtest.h>

#include <random>

#include "cube_fixture.h"
#include "light/room_light.h"
#include "light/texel_geometry.h"

namespace insitu {
namespace {

// A mild cube (texels 0.5…1.5, one 5× brighter) for the χ² test, whose expected counts come from
// a midpoint quadrature of the pdf: with the 50× spikes of random_cube the images of bright texels
// seen from x are too sharp for it.
CubeMap mild_cube(int n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.5f, 1.5f);
  CubeMap c(n);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) c.set_texel(f, i, j, Rgb::Constant(u(rng)));
  c.set_texel(kPosY, 1, 2, Rgb::Constant(5.0f));
  c.update_borders();
  return c;
}

// A window on the −x wall and a door on the +z wall.
std::vector<RoomOpening> window_and_door() {
  return {{0, Vec3f(-2.5f, 0.8f, -2.2f), Vec3f(-2.5f, 2.1f, -0.6f)}, {2, Vec3f(0.5f, 0, 3), Vec3f(1.4f, 2.1f, 3)}};
}

struct Room {
  explicit Room(CubeMap c = test::random_cube(4, 11), std::vector<RoomOpening> openings = {})
      : cube(std::move(c)),
        light(cube,
              RoomBox{Vec3f(-2.5f, 0, -3), Vec3f(2.5f, 2.6f, 3), Vec3f(-0.2f, 0.9f, -1.2f), openings, std::nullopt}) {}
  CubeMap cube;
  EnvSampler env{cube};
  RoomLight light;
};

// A sample's own pdf is the density pdf() gives its direction, and the radiance it carries is
// what radiance() finds along it: the sampler and the lookup describe one emitter.
TEST(RoomLight, SampleAgreesWithPdfAndRadiance) {
  for (const bool openings : {false, true}) {
    SCOPED_TRACE(openings ? "with openings" : "closed");
    Room r(test::random_cube(4, 11), openings ? window_and_door() : std::vector<RoomOpening>{});
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0, 1);
    for (const Vec3f& x : {Vec3f(1.0f, 0.4f, 1.5f), Vec3f(-2.3f, 2.4f, 2.8f), Vec3f(-0.2f, 0.9f, -1.2f)}) {
      int checked = 0;
      for (int k = 0; k < 2000; ++k) {
        const RoomSample s = r.light.sample(x, u(rng), u(rng), u(rng));
        if (!(s.pdf > 0)) continue;
        ++checked;
        ASSERT_NEAR(s.pdf, r.light.pdf(x, s.dir), 2e-3f * s.pdf) << k;
        // The sampled point and the box along the direction agree to float precision; a texel
        // boundary may lie between them, so the radiance is compared where it is well inside.
        float t = 0;
        int axis = 0;
        ASSERT_TRUE(r.light.exit(x, s.dir, &t, &axis));
        ASSERT_NEAR(t, s.distance, 1e-4f * s.distance);
        ASSERT_TRUE((s.radiance == r.light.radiance(x, s.dir)).all());
      }
      EXPECT_GT(checked, 1500);
    }
  }
}

// χ² of the histogram of sampled directions at a point x against ∫_bin pdf dω (midpoint
// quadrature, independent of the sampler), bins the 96 texels of a 4² direction cube around x;
// bins expecting fewer than 5 counts are pooled. (χ² − k)/√(2k) < 4 unless the sampler is wrong.
// The quadrature's total is ∫ pdf dω = 1.
void chi_square_at(const Room& r, const Vec3f& x) {
  // A bin straddles the images of texel edges (the pdf jumps there): q = 192 keeps the midpoint
  // rule's error (~1/q of a boundary bin) below the sampling noise of 50 000 samples.
  const int n = 4, q = 192, count = 50000;
  std::vector<double> hist(6 * n * n, 0.0), expected(6 * n * n, 0.0);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        double sum = 0;
        for (int b = 0; b < q; ++b)
          for (int a = 0; a < q; ++a) {
            const int ii = i * q + a, jj = j * q + b, nn = n * q;
            sum += r.light.pdf(x, texel_direction(f, ii, jj, nn)) * texel_solid_angle(ii, jj, nn);
          }
        expected[std::size_t((f * n + j) * n + i)] = sum * count;
      }
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(0, 1);
  double accepted = 0;
  for (int k = 0; k < count; ++k) {
    const RoomSample s = r.light.sample(x, u(rng), u(rng), u(rng));
    if (!(s.pdf > 0)) continue;
    accepted += 1;
    const FaceCoord fc = direction_to_face(s.dir);
    hist[std::size_t((fc.face * n + std::min(int(fc.t * n), n - 1)) * n + std::min(int(fc.s * n), n - 1))] += 1;
  }
  double chi2 = 0, total = 0, pooled_h = 0, pooled_e = 0;
  int bins = 0;
  for (std::size_t b = 0; b < hist.size(); ++b) {
    total += expected[b];
    if (expected[b] < 5) {
      pooled_h += hist[b], pooled_e += expected[b];
      continue;
    }
    chi2 += (hist[b] - expected[b]) * (hist[b] - expected[b]) / expected[b];
    ++bins;
  }
  if (pooled_e > 0) chi2 += (pooled_h - pooled_e) * (pooled_h - pooled_e) / pooled_e, ++bins;
  // ∫ pdf dω is the probability that a draw is kept (1 without openings).
  EXPECT_NEAR(total, accepted, 4 * std::sqrt(accepted) + 5e-3 * count);
  const double k = double(bins - 1);
  std::printf("chi2 %.1f over %d bins\n", chi2, bins);
  EXPECT_LT((chi2 - k) / std::sqrt(2 * k), 4.0) << "chi2 " << chi2 << " over " << bins << " bins";
}

TEST(RoomLight, ChiSquareAgainstThePdf) { chi_square_at(Room(mild_cube(4)), Vec3f(1.0f, 0.4f, 1.5f)); }

// With a window and a door, the mixture of wall, directional-portal and area-portal samples
// (rejected draws included) against the mixture's pdf, at a point that sees both openings.
TEST(RoomLight, ChiSquareWithOpenings) {
  chi_square_at(Room(mild_cube(4), window_and_door()), Vec3f(1.0f, 0.4f, 1.5f));
}

// ∫ pdf dω = 1 at points across the room, with the spiky cube: Monte Carlo over uniform directions,
// E[4π·pdf] = 1 within 4 standard errors.
TEST(RoomLight, PdfIntegratesToOne) {
  Room r;
  for (const Vec3f& x : {Vec3f(1.0f, 0.4f, 1.5f), Vec3f(-0.2f, 0.9f, -1.2f), Vec3f(2.4f, 0.05f, -2.9f)}) {
    std::mt19937 rng(4);
    std::normal_distribution<float> g(0, 1);
    const int count = 400000;
    double sum = 0, sum2 = 0;
    for (int k = 0; k < count; ++k) {
      const double v = 4 * kPi * r.light.pdf(x, Vec3f(g(rng), g(rng), g(rng)).normalized());
      sum += v;
      sum2 += v * v;
    }
    const double mean = sum / count, se = std::sqrt((sum2 / count - mean * mean) / count);
    EXPECT_NEAR(mean, 1.0, 4 * se) << x.transpose();
  }
}

// With openings the strategies' rejected draws make it a sub-density: ∫ pdf dω equals the
// probability that a draw is kept, counted from sample(), and most draws are kept.
TEST(RoomLight, WithOpeningsPdfIntegratesToTheKeptFraction) {
  Room r(test::random_cube(4, 11), window_and_door());
  for (const Vec3f& x : {Vec3f(1.0f, 0.4f, 1.5f), Vec3f(-2.4f, 1.5f, -1.0f), Vec3f(2.4f, 0.05f, -2.9f)}) {
    std::mt19937 rng(4);
    std::normal_distribution<float> g(0, 1);
    std::uniform_real_distribution<float> u(0, 1);
    const int count = 400000;
    double sum = 0, sum2 = 0, kept = 0;
    for (int k = 0; k < count; ++k) {
      const double v = 4 * kPi * r.light.pdf(x, Vec3f(g(rng), g(rng), g(rng)).normalized());
      sum += v;
      sum2 += v * v;
      kept += r.light.sample(x, u(rng), u(rng), u(rng)).pdf > 0;
    }
    const double mean = sum / count, se = std::sqrt((sum2 / count - mean * mean) / count);
    const double p = kept / count, se_p = std::sqrt(p * (1 - p) / count);
    EXPECT_NEAR(mean, p, 4 * std::hypot(se, se_p)) << x.transpose();
    EXPECT_GT(p, 0.6) << x.transpose();
  }
}

// A sun seen from the capture point through the window lights the points whose own ray toward it
// leaves through the window, at full radiance, and no other point: light through an opening is
// distant. A wall keeps the box projection.
TEST(RoomLight, SunThroughTheWindowFallsOnlyWhereTheWindowLetsItIn) {
  const Vec3f to_sun = Vec3f(-1.0f, 0.45f, 0.25f).normalized();
  // 64² faces: the sun's texel (1.4°) lies well inside the window as c sees it.
  const Room r(test::sun_cube(64, to_sun, 0.1f, 1e4f), {{0, Vec3f(-2.5f, 0.9f, -2.2f), Vec3f(-2.5f, 2.3f, -0.2f)}});
  // From (0.9, 0.5, −2.35) the sun's ray leaves through the window; from (1.5, 0.5, 2) it meets the −x wall.
  const Vec3f lit(0.9f, 0.5f, -2.35f), shade(1.5f, 0.5f, 2.0f);
  EXPECT_EQ(r.light.radiance(lit, to_sun)[0], 1e4f);
  EXPECT_EQ(r.light.radiance(shade, to_sun)[0], 0.1f);
  // The sun is drawn where it shines: a good share of the samples at the lit point carry it.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0, 1);
  int lit_hits = 0, shade_hits = 0;
  for (int k = 0; k < 4000; ++k) {
    lit_hits += r.light.sample(lit, u(rng), u(rng), u(rng)).radiance[0] > 1e3f;
    shade_hits += r.light.sample(shade, u(rng), u(rng), u(rng)).radiance[0] > 1e3f;
  }
  EXPECT_GT(lit_hits, 4000 * r.light.opening_probability() / 4);
  EXPECT_EQ(shade_hits, 0);
}

// Through the window, a direction the capture point saw as wall (steeply up, from the floor below
// it) carries RoomBox::unseen_outside where that is known, and the wall c saw along it where not;
// one c saw through the window keeps the cube's radiance either way, and every density is the
// same: only what the light is there changes, not how it is drawn.
TEST(RoomLight, TheUnseenOutsideFillsWhatTheCaptureSawAsWall) {
  const CubeMap cube = test::random_cube(16, 4);
  const RoomBox box{Vec3f(-2.5f, 0, -3), Vec3f(2.5f, 2.6f, 3), Vec3f(-0.2f, 0.9f, -1.2f), window_and_door(),
                    std::nullopt};
  RoomBox filled = box;
  filled.unseen_outside = Rgb(7, 8, 9);
  const RoomLight stand_in(cube, box), known(cube, filled);
  const Vec3f below(-2.3f, 0.1f, -1.4f), up = Vec3f(-0.2f, 1.9f, 0).normalized();
  float t = 0;
  int axis = 0;
  ASSERT_TRUE(known.exit(below, up, &t, &axis));
  ASSERT_EQ(known.openings_at(below + t * up, axis), 1);  // it leaves through the window
  ASSERT_TRUE(known.exit(box.capture, up, &t, &axis));
  ASSERT_EQ(known.openings_at(box.capture + t * up, axis), 0);  // where c saw the ceiling
  EXPECT_TRUE(known.radiance(below, up).isApprox(Rgb(7, 8, 9), 0.0f)) << known.radiance(below, up).transpose();
  EXPECT_TRUE(stand_in.radiance(below, up).isApprox(cube.lookup_nearest(up), 0.0f));
  EXPECT_EQ(known.pdf(below, up), stand_in.pdf(below, up));
  // From c toward the window's middle: seen outside, at a point on the way there.
  const Vec3f seen = (Vec3f(-2.5f, 1.45f, -1.4f) - box.capture).normalized(), on_the_way = box.capture + 1.0f * seen;
  EXPECT_TRUE(known.radiance(on_the_way, seen).isApprox(stand_in.radiance(on_the_way, seen), 0.0f));
  EXPECT_EQ(known.pdf(on_the_way, seen), stand_in.pdf(on_the_way, seen));
  // The same world as one cube (what export-blender puts behind the openings).
  const CubeMap through = known.seen_through_openings(cube);
  EXPECT_TRUE(through.lookup_nearest(up).isApprox(Rgb(7, 8, 9), 0.0f));
  EXPECT_TRUE(through.lookup_nearest(seen).isApprox(cube.lookup_nearest(seen), 0.0f));
  EXPECT_TRUE(stand_in.seen_through_openings(cube).lookup_nearest(up).isApprox(cube.lookup_nearest(up), 0.0f));
}

// Outside the box, and without one, the room is the distant cube.
TEST(RoomLight, OutsideOrWithoutABoxIsTheDistantCube) {
  Room r;
  const RoomLight distant(r.cube, std::nullopt);
  const Vec3f d = Vec3f(0.3f, -0.5f, 0.8f).normalized();
  for (const RoomLight* l : {&distant, static_cast<const RoomLight*>(&r.light)}) {
    const Vec3f x = l == &distant ? Vec3f(0.1f, 0.2f, 0.3f) : Vec3f(10, 1, 0);  // outside the box
    EXPECT_FLOAT_EQ(l->pdf(x, d), r.env.pdf(d));
    EXPECT_FLOAT_EQ(l->radiance(x, d)[0], r.env.radiance(d)[0]);
  }
}

}  // namespace
}  // namespace insitu
