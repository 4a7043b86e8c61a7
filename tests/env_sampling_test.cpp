// Environment importance sampling (light/env_sampling.h): the sampler against its own pdf.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "cube_fixture.h"
#include "light/texel_geometry.h"
#include "light/env_sampling.h"

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

// The guide table's texel is the bisection's, bit for bit: at random u, on a fine grid, at every
// guide boundary g/G (where rounding could put u in the guide entry after its own) and beside it,
// at the ends, and for input outside [0, 1) or NaN. A cube with
// a very bright texel and many dark ones makes the CDF steps as uneven as a sun's.
TEST(EnvSampling, GuideTableFindsTheTexelBisectionFinds) {
  CubeMap cube = random_cube(16, 5);
  cube.set_texel(2, 3, 7, Rgb(1e5f, 9e4f, 8e4f));
  for (int i = 0; i < 16; ++i) cube.set_texel(4, i, 2, Rgb::Zero());
  cube.update_borders();
  const EnvSampler s(cube);
  auto same = [&](float u) {
    const EnvSample a = s.sample(u, 0.3f, 0.6f), b = s.sample_by_bisection(u, 0.3f, 0.6f);
    return a.dir == b.dir && a.pdf == b.pdf;
  };
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> uniform(0, 1);
  for (int k = 0; k < 200000; ++k) ASSERT_TRUE(same(uniform(rng))) << k;
  // Every float from 0 to 1 in steps of 2⁻¹⁶, and their neighbours.
  for (int k = 0; k <= 65536; ++k) {
    const float u = float(k) / 65536.0f;
    ASSERT_TRUE(same(u) && same(std::nextafter(u, 0.0f)) && same(std::nextafter(u, 2.0f))) << u;
  }
  const int texels = 6 * 16 * 16 / 8 + 1;  // G
  for (int g = 0; g <= texels; ++g) {
    const float u = float(double(g) / texels);
    ASSERT_TRUE(same(u) && same(std::nextafter(u, 0.0f)) && same(std::nextafter(u, 2.0f))) << g;
  }
  for (float u : {0.0f, 1.0f, -0.5f, 7.0f, std::nextafter(1.0f, 0.0f), std::numeric_limits<float>::quiet_NaN()})
    EXPECT_TRUE(same(u)) << u;
}

// The sampler keeps its CDF in float, each entry float_at_or_above the double sum: for every float
// u the texel upper_bound finds is the double CDF's. Steps as uneven as a sun's and far below a
// float's resolution (where neighbouring entries round to one float), probed at every entry's
// neighbouring floats, where rounding to nearest instead would pick the next texel.
TEST(EnvSampling, AFloatCdfRoundedUpPicksTheTexelsOfTheDoubleOne) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<double> w(5000);
  for (double& x : w) x = std::pow(10.0, -12 * unit(rng));
  w[1234] = 1e4;
  double total = 0;
  for (double x : w) total += x;
  std::vector<double> cdf_d{0.0};
  std::vector<float> cdf_f{0.0f};
  for (double x : w) {
    cdf_d.push_back(cdf_d.back() + x / total);
    cdf_f.push_back(float_at_or_above(cdf_d.back()));
    ASSERT_GE(double(cdf_f.back()), cdf_d.back());
    ASSERT_LT(double(std::nextafter(cdf_f.back(), 0.0f)), cdf_d.back());
  }
  auto same = [&](float u) {
    return std::upper_bound(cdf_d.begin() + 1, cdf_d.end(), double(u)) - cdf_d.begin() ==
           std::upper_bound(cdf_f.begin() + 1, cdf_f.end(), u) - cdf_f.begin();
  };
  for (const double c : cdf_d) {
    const float near = float(c);
    for (float u : {near, std::nextafter(near, 0.0f), std::nextafter(near, 2.0f)}) ASSERT_TRUE(same(u)) << c;
  }
  std::uniform_real_distribution<float> uniform(0, 1);
  for (int k = 0; k < 100000; ++k) ASSERT_TRUE(same(uniform(rng))) << k;
}

// A sampler that shares another's records (RoomLight's side samplers) is the sampler of its own
// cube, bit for bit: the same texel, direction and pdf for every u, and the same pdf and radiance
// in every direction, where its cube equals the records' and where it differs (a texel of each
// 16 differs here, the rest of the cube is the records' own).
TEST(EnvSampling, ASamplerSharingRecordsIsTheSamplerOfItsOwnCube) {
  const int n = 16;
  const CubeMap records_cube = random_cube(n, 11);
  CubeMap cube = records_cube;
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> uniform(0, 1);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (uniform(rng) < 1.0f / 16) cube.set_texel(f, i, j, Rgb(uniform(rng), 4 * uniform(rng), 0.5f));
  cube.update_borders();
  auto share = [](int f, int i, int j) { return f == 4 ? 1.0 : 0.25 * double((i + j) % 5); };
  const EnvSampler records(records_cube);
  const EnvSampler shared(cube, records, share, false), own(cube, share, false);
  for (int k = 0; k < 100000; ++k) {
    const float u = uniform(rng), s = uniform(rng), t = uniform(rng);
    const EnvSample a = shared.sample(u, s, t), b = own.sample(u, s, t);
    ASSERT_TRUE(a.dir == b.dir && a.pdf == b.pdf) << k;
  }
  std::normal_distribution<float> g(0, 1);
  for (int k = 0; k < 100000; ++k) {
    const Vec3f d = Vec3f(g(rng), g(rng), g(rng)).normalized();
    ASSERT_EQ(shared.pdf(d), own.pdf(d)) << d.transpose();
    ASSERT_TRUE((shared.radiance(d) == cube.lookup_nearest(d)).all()) << d.transpose();
    const EnvLookup l = shared.lookup(d);
    ASSERT_TRUE(l.pdf == own.pdf(d) && (l.radiance == cube.lookup_nearest(d)).all()) << d.transpose();
  }
  EXPECT_THROW(EnvSampler(random_cube(8, 1), records, share), std::logic_error);
  EXPECT_THROW(EnvSampler(cube, shared, share), std::logic_error);
}

// radiance() is the cube's nearest texel, bit for bit, in every direction (record layout), and
// lookup() gives that radiance and pdf()'s density from its one projection.
TEST(EnvSampling, RadianceIsTheCubesNearestTexel) {
  const CubeMap cube = random_cube(32, 7);
  const EnvSampler s(cube);
  std::mt19937 rng(8);
  std::normal_distribution<float> g(0, 1);
  for (int k = 0; k < 100000; ++k) {
    const Vec3f d = Vec3f(g(rng), g(rng), g(rng)).normalized();
    ASSERT_TRUE((s.radiance(d) == cube.lookup_nearest(d)).all()) << d.transpose();
    const EnvLookup l = s.lookup(d);
    ASSERT_TRUE(l.pdf == s.pdf(d) && (l.radiance == cube.lookup_nearest(d)).all()) << d.transpose();
  }
}

}  // namespace
}  // namespace insitu
