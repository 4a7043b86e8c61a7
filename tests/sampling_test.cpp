#include <gtest/gtest.h>

#include <random>

#include "core/sampling.h"

namespace insitu {
namespace {

std::vector<Vec3f> test_normals() {
  std::vector<Vec3f> ns = {{1, 0, 0},
                           {-1, 0, 0},
                           {0, 1, 0},
                           {0, 0, -1},
                           Vec3f(0.9f, 0.1f, 0).normalized(),
                           Vec3f(0.89999f, 0.43589f, 0).normalized()};
  std::mt19937 rng(1);
  std::normal_distribution<float> g(0, 1);
  for (int k = 0; k < 50; ++k) ns.push_back(Vec3f(g(rng), g(rng), g(rng)).normalized());
  return ns;
}

// (t, b, n) is orthonormal and right-handed for every normal, also on and near the axes where the
// helper axis switches; to_local and to_world are inverses.
TEST(Sampling, FrameIsOrthonormalEverywhere) {
  for (const Vec3f& n : test_normals()) {
    const Frame f(n);
    EXPECT_NEAR(f.t.norm(), 1, 1e-6f);
    EXPECT_NEAR(f.b.norm(), 1, 1e-6f);
    EXPECT_NEAR(f.t.dot(f.b), 0, 1e-6f);
    EXPECT_NEAR(f.t.dot(f.n), 0, 1e-6f);
    EXPECT_NEAR(f.b.dot(f.n), 0, 1e-6f);
    EXPECT_NEAR(f.t.cross(f.b).dot(f.n), 1, 1e-6f);
    const Vec3f v(0.3f, -0.5f, 0.8f);
    EXPECT_LT((f.to_world(f.to_local(v)) - v).norm(), 1e-6f);
  }
}

// χ² of cosine-weighted samples against their pdf cos θ/π: over the hemisphere
// ∫ cos θ/π dω = ∫∫ d(sin²θ) dφ / 2π, so sin²θ and φ are independent and uniform and each of the
// 10 × 10 bins of (sin²θ, φ) expects N/100 samples. Relative to a normal n the same holds for
// sin²θ = 1 − (ω·n)².
TEST(Sampling, CosineSamplesFollowTheirPdf) {
  const Vec3f n = Vec3f(0.3f, 0.8f, -0.5f).normalized();
  const Frame f(n);
  const int count = 100000, bins = 10;
  std::vector<double> hist(bins * bins, 0.0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0, 1);
  for (int k = 0; k < count; ++k) {
    const Vec3f w = cosine_sample(n, u(rng), u(rng));
    ASSERT_NEAR(w.norm(), 1, 1e-5f);
    ASSERT_GE(w.dot(n), 0);
    const Vec3f l = f.to_local(w);
    const float sin2 = std::clamp(1 - l.z() * l.z(), 0.0f, 1.0f);
    const float phi = std::atan2(l.y(), l.x()) + kPiF;
    hist[std::size_t(std::min(int(sin2 * bins), bins - 1) * bins + std::min(int(phi / (2 * kPiF) * bins), bins - 1))] +=
        1;
  }
  const double expected = double(count) / (bins * bins);
  double chi2 = 0;
  for (double h : hist) chi2 += (h - expected) * (h - expected) / expected;
  const double k = bins * bins - 1;
  EXPECT_LT((chi2 - k) / std::sqrt(2 * k), 4.0) << "chi2 " << chi2;
}

// The real power heuristic: the weights of two strategies sum to 1 across twelve orders of
// magnitude, and the stronger strategy gets the larger weight.
TEST(Sampling, PowerHeuristicWeightsSumToOne) {
  for (float a : {1e-6f, 0.1f, 1.0f, 7.0f, 1e5f})
    for (float b : {1e-6f, 0.3f, 1.0f, 1e4f}) {
      EXPECT_NEAR(power_heuristic(a, b) + power_heuristic(b, a), 1.0f, 1e-6f) << a << " " << b;
      if (a > b) {
        EXPECT_GT(power_heuristic(a, b), 0.5f);
      }
    }
  EXPECT_FLOAT_EQ(power_heuristic(2, 1), 0.8f);  // 4 / (4 + 1)
}

// The ray offset is relative to the position's magnitude, with a floor of 1 mm · 10⁻⁵.
TEST(Sampling, RayOffsetScalesWithThePosition) {
  const Vec3f up(0, 1, 0);
  EXPECT_FLOAT_EQ((offset_origin(Vec3f(1000, 0, 0), up) - Vec3f(1000, 0, 0)).y(), 1e-2f);
  EXPECT_FLOAT_EQ((offset_origin(Vec3f(0, 0, 1), up) - Vec3f(0, 0, 1)).y(), 1e-5f);
  EXPECT_FLOAT_EQ(offset_origin(Vec3f(0, 0, 1e-7f), up).y(), 1e-8f);
}

}  // namespace
}  // namespace insitu
