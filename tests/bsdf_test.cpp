#include <gtest/gtest.h>

#include "render/bsdf.h"
#include "core/sampler.h"

namespace insitu {
namespace {

Vec3f direction_at(float theta_deg) {
  const float t = float(deg_to_rad(theta_deg));
  return {std::sin(t), 0.0f, std::cos(t)};
}

struct Mc {
  double mean, se;
};

// ∫ g(ωi) dω over the upper hemisphere by uniform sampling (pdf 1/2π).
template <class G>
Mc hemisphere_integral(G g, int count, std::uint64_t seed) {
  double sum = 0, sum2 = 0;
  for (int k = 0; k < count; ++k) {
    Sampler s(seed, std::uint64_t(k), 0);
    const float z = s.next(), phi = 2 * kPiF * s.next(), r = std::sqrt(std::max(0.0f, 1 - z * z));
    const double x = 2 * kPi * g(Vec3f(r * std::cos(phi), r * std::sin(phi), z));
    sum += x;
    sum2 += x * x;
  }
  const double m = sum / count;
  return {m, std::sqrt((sum2 / count - m * m) / count)};
}

// E[f·cos/pdf] over the BSDF's own samples (failed samples count 0).
Mc sampled_albedo(const Bsdf& b, const Vec3f& wo, int count, std::uint64_t seed) {
  double sum = 0, sum2 = 0;
  for (int k = 0; k < count; ++k) {
    Sampler s(seed, std::uint64_t(k), 1);
    BsdfSample bs;
    const float ul = s.next(), u1 = s.next(), u2 = s.next();
    const double x = b.sample(wo, ul, u1, u2, &bs) ? double(bs.weight[1]) : 0.0;
    sum += x;
    sum2 += x * x;
  }
  const double m = sum / count;
  return {m, std::sqrt((sum2 / count - m * m) / count)};
}

TEST(BsdfTest, WithoutKsItIsLambertian) {
  const Bsdf b(Rgb(0.5f, 0.25f, 1.0f), Rgb::Zero(), 0.3f);
  EXPECT_FALSE(b.glossy());
  const Vec3f wo = direction_at(40), wi = direction_at(-10);
  EXPECT_TRUE(b.eval(wo, wi).isApprox(Rgb(0.5f, 0.25f, 1.0f) / kPiF));
  BsdfSample s;
  ASSERT_TRUE(b.sample(wo, 0.3f, 0.4f, 0.7f, &s));
  EXPECT_TRUE(s.weight.isApprox(Rgb(0.5f, 0.25f, 1.0f), 1e-5f));
  EXPECT_NEAR(s.pdf, s.wi.z() / kPiF, 1e-6f);
}

// The sampler draws from pdf(): the mean weight of its samples equals ∫ f cos dω computed by
// uniform hemisphere sampling, and ∫ pdf dω equals the fraction of samples that succeed.
TEST(BsdfTest, SamplingMatchesEvalAndPdf) {
  for (float alpha : {0.05f, 0.3f, 1.0f})
    for (float theta : {0.0f, 60.0f, 85.0f}) {
      const Bsdf b(Rgb::Constant(0.5f), Rgb::Constant(0.3f), alpha);
      const Vec3f wo = direction_at(theta);
      const Mc by_sampling = sampled_albedo(b, wo, 400000, 3);
      const Mc by_quadrature =
          hemisphere_integral([&](const Vec3f& wi) { return double(b.eval(wo, wi)[1]) * wi.z(); }, 400000, 4);
      EXPECT_NEAR(by_sampling.mean, by_quadrature.mean, 4 * std::hypot(by_sampling.se, by_quadrature.se))
          << "alpha " << alpha << " theta " << theta;
      const Mc pdf_integral = hemisphere_integral([&](const Vec3f& wi) { return double(b.pdf(wo, wi)); }, 400000, 5);
      int ok = 0;
      const int n = 200000;
      for (int k = 0; k < n; ++k) {
        Sampler s(6, std::uint64_t(k), 2);
        BsdfSample bs;
        const float ul = s.next(), u1 = s.next(), u2 = s.next();
        ok += b.sample(wo, ul, u1, u2, &bs);
      }
      const double p = double(ok) / n, se_p = std::sqrt(p * (1 - p) / n);
      EXPECT_NEAR(pdf_integral.mean, p, 4 * std::hypot(pdf_integral.se, se_p) + 1e-3)
          << "alpha " << alpha << " theta " << theta;
    }
}

// A white base under any specular layer reflects at most what arrives: ∫ f cos dω ≤ 1.
TEST(BsdfTest, EnergyIsConserved) {
  for (float f0 : {0.04f, 0.5f, 1.0f})
    for (float alpha : {0.02f, 0.2f, 0.8f})
      for (float theta : {0.0f, 45.0f, 80.0f, 89.0f}) {
        const Bsdf b(Rgb::Ones(), Rgb::Constant(f0), alpha);
        const Mc a = sampled_albedo(b, direction_at(theta), 100000, 7);
        EXPECT_LE(a.mean, 1.0 + 4 * a.se + 1e-3) << "f0 " << f0 << " alpha " << alpha << " theta " << theta;
      }
}

}  // namespace
}  // namespace insitu
