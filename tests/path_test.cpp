#include <gtest/gtest.h>

#include <random>

#include "cube_fixture.h"
#include "render/env_sampling.h"
#include "light/equirect.h"
#include "integrators/registry.h"
#include "light/irradiance.h"
#include "render/mesh.h"
#include "scene/scene_file.h"
#include "box_fixture.h"
#include "test_util.h"
#include "light/texel_geometry.h"

namespace insitu {
namespace {

using test::random_cube;

// χ² of the texel histogram of 200 000 samples against P_i = pdf integrated over texel i (which
// the sampler must reproduce); with k − 1 = 95 degrees of freedom the statistic is within
// (χ² − k)/√(2k) < 4 unless the sampler is wrong.
TEST(EnvSampling, ChiSquareAgainstThePdf) {
  const int n = 4;
  const CubeMap cube = random_cube(n, 1);
  const EnvSampler s(cube);
  const int count = 200000;
  std::vector<double> hist(6 * n * n, 0.0), expected(6 * n * n, 0.0);
  // Expected: ∫_texel pdf dω by a fine midpoint quadrature in solid angle (independent of the
  // sampler's own probabilities).
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int q = 16;
        double sum = 0;
        for (int b = 0; b < q; ++b)
          for (int a = 0; a < q; ++a) {
            const int ii = i * q + a, jj = j * q + b, nn = n * q;
            sum += s.pdf(texel_direction(f, ii, jj, nn)) * texel_solid_angle(ii, jj, nn);
          }
        expected[std::size_t((f * n + j) * n + i)] = sum * count;
      }
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(0, 1);
  for (int k = 0; k < count; ++k) {
    const EnvSample e = s.sample(u(rng), u(rng), u(rng));
    ASSERT_NEAR(e.pdf, s.pdf(e.dir), 1e-3f * e.pdf);
    const FaceCoord fc = direction_to_face(e.dir);
    hist[std::size_t((fc.face * n + std::min(int(fc.t * n), n - 1)) * n + std::min(int(fc.s * n), n - 1))] += 1;
  }
  double chi2 = 0, total = 0;
  for (std::size_t b = 0; b < hist.size(); ++b) {
    chi2 += (hist[b] - expected[b]) * (hist[b] - expected[b]) / expected[b];
    total += expected[b];
  }
  EXPECT_NEAR(total, count, 1e-3 * count);  // the pdf integrates to 1
  const double k = double(hist.size() - 1);
  EXPECT_LT((chi2 - k) / std::sqrt(2 * k), 4.0) << "chi2 " << chi2;
}

// ∫ pdf dω = 1: Monte Carlo over uniform directions, E[4π·pdf] = 1 within 4 standard errors.
TEST(EnvSampling, PdfIntegratesToOne) {
  const EnvSampler s(random_cube(8, 3));
  std::mt19937 rng(4);
  std::normal_distribution<float> g(0, 1);
  const int count = 400000;
  double sum = 0, sum2 = 0;
  for (int k = 0; k < count; ++k) {
    const double x = 4 * kPi * s.pdf(Vec3f(g(rng), g(rng), g(rng)).normalized());
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / count, se = std::sqrt((sum2 / count - mean * mean) / count);
  EXPECT_NEAR(mean, 1.0, 4 * se);
}

// A box with flat faces (shading normal = geometric normal), Kd given, scaled.
struct Estimate {
  Rgb mean, se;
};

Estimate estimate(const Integrator& integ, const Ray& ray, int samples, std::uint64_t pixel) {
  Eigen::Array3d sum = Eigen::Array3d::Zero(), sum2 = Eigen::Array3d::Zero();
  for (int k = 0; k < samples; ++k) {
    Sampler s(5, pixel, std::uint64_t(k));
    const CameraSample cs = integ.sample(ray, s);
    const Eigen::Array3d x = (cs.radiance * cs.coverage).cast<double>();
    sum += x;
    sum2 += x * x;
  }
  const Eigen::Array3d mean = sum / samples;
  return {mean.cast<float>(), ((sum2 / samples - mean * mean) / samples).sqrt().cast<float>()};
}

// White furnace: reflectance 1 in a constant environment L reflects exactly L, for `path` within
// its standard error, for `irradiance` exactly — at 1 mm, 1 m and 1 km.
TEST(Path, WhiteFurnaceAtEveryScale) {
  test::TempDir dir;
  CubeMap env(8);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) env.set_texel(f, i, j, Rgb(0.7f, 0.7f, 0.7f));
  env.update_borders();
  for (double scale : {1e-3, 1.0, 1e3}) {
    const EmbreeScene box = test::make_box(dir, "1 1 1", scale);
    RenderInputs in;
    in.objects = &box;
    in.environment = &env;
    const auto path = make_integrator("path", in);
    // Inside a uniformly emitting room box (room_light.h), captured off-centre: the same.
    RenderInputs in_room = in;
    in_room.room_box = true;
    in_room.box_min = Vec3f(-6, -6, -6) * float(scale);
    in_room.box_max = Vec3f(6, 6, 7) * float(scale);
    in_room.capture = Vec3f(1.5f, 0.5f, -2) * float(scale);
    const auto path_room = make_integrator("path", in_room);
    const auto irr = make_integrator("irradiance", in);
    const std::vector<Ray> rays = {{Vec3f(0.3f, 0.2f, 5) * float(scale), Vec3f(-0.05f, 0.02f, -1).normalized()},
                                   {Vec3f(3, 4, 2) * float(scale), -Vec3f(3, 4, 2).normalized()}};
    for (std::size_t r = 0; r < rays.size(); ++r) {
      const Estimate e = estimate(*path, rays[r], 4000, r);
      EXPECT_NEAR(e.mean[0], 0.7f, 4 * e.se[0] + 1e-6f) << "scale " << scale;
      const Estimate e_room = estimate(*path_room, rays[r], 4000, r);
      EXPECT_NEAR(e_room.mean[0], 0.7f, 4 * e_room.se[0] + 1e-6f) << "room box, scale " << scale;
      Sampler s(1, 0, 0);
      EXPECT_NEAR(irr->sample(rays[r], s).radiance[0], 0.7f, 1e-4f);
    }
  }
}

// For a convex object alone (nothing to occlude, no interreflection), `path` equals ρ/π times the
// exact irradiance at the normal (the brute-force reference), within its standard error.
TEST(Path, ConvexObjectEqualsExactIrradiance) {
  INSITU_REQUIRE_SHARED();
  test::TempDir dir;
  const CubeMap env = cube_from_equirect(linearize(read_image_file(test::shared_data() + "/hdri/sunset.exr")), 16);
  const EmbreeScene box = test::make_box(dir, "0.5 0.4 0.3", 1.0);
  RenderInputs in;
  in.objects = &box;
  in.environment = &env;
  const auto path = make_integrator("path", in);
  const struct { Ray ray; Vec3d normal; } cases[] = {
      {{Vec3f(0.2f, 0.1f, 5), Vec3f(0, 0, -1)}, {0, 0, 1}},
      {{Vec3f(0.1f, 5, -0.3f), Vec3f(0, -1, 0)}, {0, 1, 0}},
      {{Vec3f(-5, 0.2f, 0.4f), Vec3f(1, 0, 0)}, {-1, 0, 0}},
      {{Vec3f(0.3f, -5, 0.1f), Vec3f(0, 1, 0)}, {0, -1, 0}},
  };
  for (std::size_t c = 0; c < 4; ++c) {
    const Estimate e = estimate(*path, cases[c].ray, 20000, c);
    const Rgb expected = Rgb(0.5f, 0.4f, 0.3f) * irradiance_reference(env, cases[c].normal) / kPiF;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(e.mean[k], expected[k], 4 * e.se[k] + 1e-5f * expected[k]) << "case " << c << " channel " << k;
  }
}

}  // namespace
}  // namespace insitu
