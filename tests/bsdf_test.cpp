#include <functional>
#include <gtest/gtest.h>

#include "render/bsdf.h"
#include "render/ggx.h"
#include "render/gtr1.h"
#include "render/velvet.h"
#include "core/sampler.h"
#include "bsdf_sampling.h"
#include "chi2.h"
#include "test_util.h"

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
  return {m, std::sqrt(std::max(0.0, sum2 / count - m * m) / count)};
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
  return {m, std::sqrt(std::max(0.0, sum2 / count - m * m) / count)};
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
      const test::Fraction ok = test::success_fraction(b, wo);
      EXPECT_NEAR(pdf_integral.mean, ok.p, 4 * std::hypot(pdf_integral.se, ok.se) + 1e-3)
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

namespace insitu {
namespace {

// ∫ f cos dω of one lobe set, sampled by the BSDF itself, at an angle of incidence.
double albedo(const Bsdf& b, float theta_deg, int count = 200000) {
  return sampled_albedo(b, direction_at(theta_deg), count, 11).mean;
}

// The χ² score (χ² − dof)/√(2 dof) of a BSDF's samples against a density `pdf(wi)`: (cos θ, φ)
// bins, each bin's expected mass by an 8 × 8 midpoint rule (dω = d cos θ dφ); bins expecting fewer
// than 5 samples are pooled. Below 4 for a sampler that draws from `pdf`.
template <class Pdf>
double chi2_score(const Bsdf& b, const Vec3f& wo, Pdf pdf, double* chi2_out = nullptr) {
  constexpr int kTheta = 16, kPhi = 32, kN = 400000;
  std::vector<double> observed(kTheta * kPhi, 0.0), expected(kTheta * kPhi, 0.0);
  for (int k = 0; k < kN; ++k) {
    Sampler s(21, std::uint64_t(k), 0);
    BsdfSample bs;
    const float ul = s.next(), u1 = s.next(), u2 = s.next();
    if (!b.sample(wo, ul, u1, u2, &bs)) continue;
    const int i = std::min(kTheta - 1, int(bs.wi.z() * kTheta));
    const float phi = std::atan2(bs.wi.y(), bs.wi.x()) + kPiF;
    observed[std::size_t(i * kPhi + std::min(kPhi - 1, int(phi / (2 * kPiF) * kPhi)))] += 1;
  }
  for (int i = 0; i < kTheta; ++i)
    for (int j = 0; j < kPhi; ++j)
      for (int a = 0; a < 8; ++a)
        for (int c = 0; c < 8; ++c) {
          const float z = (float(i) + (float(a) + 0.5f) / 8) / kTheta;
          const float phi = (float(j) + (float(c) + 0.5f) / 8) / kPhi * 2 * kPiF - kPiF;
          const float r = std::sqrt(1 - z * z);
          const Vec3f wi(r * std::cos(phi), r * std::sin(phi), z);
          const double d_omega = (1.0 / kTheta) * (2 * kPi / kPhi) / 64;
          expected[std::size_t(i * kPhi + j)] += kN * pdf(wi) * d_omega;
        }
  return test::chi2_score_of(observed, expected, chi2_out);
}

// reflect(ωo, h), h from GGX's visible normals, follows ggx::reflection_pdf.
TEST(BsdfTest, VisibleNormalSamplesFollowTheirPdf) {
  for (float alpha : {0.08f, 0.3f, 0.9f})
    for (float theta : {10.0f, 50.0f, 80.0f}) {
      const Bsdf metal = Bsdf::principled(Rgb::Ones(), 1.0f, std::sqrt(alpha), 0.5f);
      const Vec3f wo = direction_at(theta);
      double chi2 = 0;
      EXPECT_LT(chi2_score(
                    metal, wo, [&](const Vec3f& wi) { return ggx::reflection_pdf(wo, wi, alpha); }, &chi2),
                4.0)
          << "alpha " << alpha << " theta " << theta << " chi2 " << chi2;
    }
}

TEST(BsdfTest, DielectricFresnelHasItsKnownValues) {
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f), 0.04f, 1e-6f);  // ((η − 1)/(η + 1))²
  EXPECT_NEAR(fresnel_dielectric(0.0f, 1.5f), 1.0f, 1e-6f);   // grazing
  EXPECT_EQ(fresnel_dielectric(0.1f, 1 / 1.5f), 1.0f);        // total internal reflection
  // Brewster's angle, tan θ_B = η: the p-polarized half vanishes, R = ½ R_s.
  const float theta_b = std::atan(1.5f), ci = std::cos(theta_b), ct = std::cos(kPiF / 2 - theta_b);
  const float rs = (ci - 1.5f * ct) / (ci + 1.5f * ct);
  EXPECT_NEAR(fresnel_dielectric(ci, 1.5f), 0.5f * rs * rs, 1e-6f);
}

// The principled model draws from its own pdf (as the obj model in SamplingMatchesEvalAndPdf).
TEST(BsdfTest, PrincipledSamplingMatchesEvalAndPdf) {
  for (float metallic : {0.0f, 0.5f})
    for (float roughness : {0.2f, 0.7f})
      for (float theta : {0.0f, 70.0f}) {
        const Bsdf b = Bsdf::principled(Rgb(0.6f, 0.4f, 0.2f), metallic, roughness, 0.5f);
        const Vec3f wo = direction_at(theta);
        const Mc by_sampling = sampled_albedo(b, wo, 400000, 3);
        const Mc by_quadrature =
            hemisphere_integral([&](const Vec3f& wi) { return double(b.eval(wo, wi)[1]) * wi.z(); }, 400000, 4);
        EXPECT_NEAR(by_sampling.mean, by_quadrature.mean, 4 * std::hypot(by_sampling.se, by_quadrature.se))
            << "metallic " << metallic << " roughness " << roughness << " theta " << theta;
        const Mc pdf_integral = hemisphere_integral([&](const Vec3f& wi) { return double(b.pdf(wo, wi)); }, 400000, 5);
        EXPECT_LE(pdf_integral.mean, 1.0 + 4 * pdf_integral.se);
      }
}

// White furnace, lobe by lobe. A smooth white metal is lossless (F = 1 everywhere; at α = 0.0025
// GGX's single scattering loses < 0.1 %); a rough one loses what single scattering loses, never
// gains. The diffuse lobe of a smooth surface, seen head-on, reflects 1 − ½·∫F_L cos/π dω =
// 1 − ½·2∫(1 − μ)^5 μ dμ = 1 − 1/42 (F_V = 0, no retro-reflection at r = 0).
TEST(BsdfTest, PrincipledLobesPassTheWhiteFurnace) {
  EXPECT_NEAR(albedo(Bsdf::principled(Rgb::Ones(), 1.0f, 0.05f, 0.5f), 0.0f), 1.0, 2e-3);
  EXPECT_NEAR(albedo(Bsdf::principled(Rgb::Ones(), 1.0f, 0.05f, 0.5f), 60.0f), 1.0, 2e-3);
  for (float r : {0.3f, 0.6f, 1.0f})
    for (float theta : {0.0f, 45.0f, 85.0f})
      EXPECT_LE(albedo(Bsdf::principled(Rgb::Ones(), 1.0f, r, 0.5f), theta), 1.0 + 2e-3) << r << " " << theta;
  EXPECT_NEAR(albedo(Bsdf::principled(Rgb::Ones(), 0.0f, 0.0f, 0.0f), 0.0f, 400000), 1.0 - 1.0 / 42, 2e-3);
  for (float theta : {0.0f, 45.0f, 85.0f})
    EXPECT_LE(albedo(Bsdf::principled(Rgb::Ones(), 0.0f, 0.0f, 0.0f), theta), 1.0 + 2e-3) << theta;
  // A coloured metal seen head-on reflects its colour (F_H = 0 at ωi·h = 1).
  const Bsdf gold = Bsdf::principled(Rgb(1.0f, 0.78f, 0.34f), 1.0f, 0.05f, 0.5f);
  EXPECT_NEAR(sampled_albedo(gold, direction_at(0), 100000, 12).mean, 0.78, 3e-3);
}

// Cycles 3.4 adds its diffuse and specular lobes: a smooth white dielectric seen at grazing
// angles reflects nearly all of the light specularly (F → 1) and its diffuse half besides. The
// sum equals the lobes' albedos taken apart (diffuse: specular 0; specular: the same Fresnel
// on a black base), which is what Cycles computes.
TEST(BsdfTest, PrincipledGainsWhatCyclesGains) {
  for (float theta : {0.0f, 60.0f, 85.0f}) {
    const double whole = albedo(Bsdf::principled(Rgb::Ones(), 0.0f, 0.3f, 0.5f), theta, 400000);
    const double diffuse = albedo(Bsdf::principled(Rgb::Ones(), 0.0f, 0.3f, 0.0f), theta, 400000);
    const double specular = albedo(Bsdf::principled(Rgb::Zero(), 0.0f, 0.3f, 0.5f), theta, 400000);
    EXPECT_NEAR(whole, diffuse + specular, 6e-3) << theta;
    if (theta == 85.0f) {
      EXPECT_GT(whole, 1.05);
    }
  }
}

}  // namespace
}  // namespace insitu

namespace insitu {
namespace {

// A clear coat alone: black base, no specular (Cycles's F0 = 0.08·specular), coat c of roughness rc.
Bsdf coat_only(float c, float rc) {
  PrincipledParams p;
  p.base = Rgb::Zero(), p.specular = 0.0f, p.clearcoat = c, p.clearcoat_roughness = rc;
  return Bsdf::principled(p);
}

// GTR1 is normalized: ∫ D(h) cos θ_h dω_h = 2π ∫₀¹ D(μ) μ dμ = 1, by a midpoint rule fine enough
// for the narrowest peak (half width ~α² in 1 − μ).
// ∫ D(μ) μ dω = 2π ∫₀¹ D(μ) μ dμ by the midpoint rule: a microfacet distribution is normalized.
double projected_area(const std::function<float(float)>& d) {
  const int n = 2000000;
  double sum = 0;
  for (int k = 0; k < n; ++k) {
    const double mu = (k + 0.5) / n;
    sum += double(d(float(mu))) * mu;
  }
  return 2 * kPi * sum / n;
}

TEST(BsdfTest, Gtr1IsNormalized) {
  for (float alpha : {0.01f, 0.1f, 0.5f, 1.0f})
    EXPECT_NEAR(projected_area([&](float mu) { return gtr1::d(mu, alpha); }), 1.0, 2e-3) << alpha;
}

// The coat's directions are drawn, as Cycles draws them, from GGX's visible normals at α = rc²
// (α ≥ 0.09: narrower peaks are not resolved by the bins' midpoint rule).
TEST(BsdfTest, ClearCoatSamplesFollowGgxVisibleNormals) {
  for (float rc : {0.3f, 0.6f, 0.9f})
    for (float theta : {10.0f, 50.0f, 80.0f}) {
      const Bsdf coat = coat_only(1.0f, rc);
      const Vec3f wo = direction_at(theta);
      double chi2 = 0;
      EXPECT_LT(chi2_score(
                    coat, wo, [&](const Vec3f& wi) { return ggx::reflection_pdf(wo, wi, rc * rc); }, &chi2),
                4.0)
          << "rc " << rc << " theta " << theta << " chi2 " << chi2;
    }
}

// Each coat sample weighs what Cycles's does: eval / pdf = ¼·c·F_d(ωi·h, 1.5)·G1(ωi; 0.25), the
// GTR1 density and G1(ωo) cancelling between its eval and its reported pdf.
TEST(BsdfTest, ClearCoatWeighsItsSamplesAsCycles) {
  const Bsdf coat = coat_only(0.8f, 0.2f);
  for (int k = 0; k < 1000; ++k) {
    Sampler s(31, std::uint64_t(k), 0);
    const Vec3f wo = direction_at(85.0f * s.next());
    BsdfSample bs;
    const float ul = s.next(), u1 = s.next(), u2 = s.next();
    if (!coat.sample(wo, ul, u1, u2, &bs)) continue;
    const Vec3f h = (wo + bs.wi).normalized();
    const float expected = 0.25f * 0.8f * fresnel_dielectric(bs.wi.dot(h), 1.5f) * ggx::g1(bs.wi.z(), 0.25f);
    EXPECT_NEAR(bs.weight[0], expected, 1e-4f * expected + 1e-7f) << k;
  }
}

// A coat about its own normal n_c, tilted 25° from the shading normal +z (a normal map bends the
// rest, bsdf.h: set_coat_normal), is the untilted coat turned: its f is the untilted f of the
// directions in n_c's frame (0 below n_c), its samples follow the turned GGX visible-normal density
// (those below +z are no sample), and its pdf is the untilted pdf so turned.
TEST(BsdfTest, ClearCoatAboutItsOwnNormalIsTheCoatTurned) {
  const float tilt = float(deg_to_rad(25.0f));
  const Vec3f n_coat(std::sin(tilt), 0.0f, std::cos(tilt));
  const Frame coat_frame(n_coat);
  for (float rc : {0.3f, 0.6f})
    for (float theta : {10.0f, 60.0f, -60.0f}) {
      Bsdf tilted = coat_only(1.0f, rc);
      tilted.set_coat_normal(n_coat);
      const Bsdf plain = coat_only(1.0f, rc);
      const Vec3f wo = direction_at(theta);
      const Vec3f wo_c = coat_frame.to_local(wo);
      for (int k = 0; k < 200; ++k) {
        Sampler s(41, std::uint64_t(k), 0);
        const float z = s.next(), phi = 2 * kPiF * s.next(), r = std::sqrt(1 - z * z);
        const Vec3f wi(r * std::cos(phi), r * std::sin(phi), z);
        const Vec3f wi_c = coat_frame.to_local(wi);
        const float f = wi_c.z() > 0 && wo_c.z() > 0 ? plain.eval(wo_c, wi_c)[0] : 0.0f;
        ASSERT_NEAR(tilted.eval(wo, wi)[0], f, 1e-5f * f + 1e-7f) << rc << " " << theta << " " << k;
        const float pdf = wi_c.z() > 0 && wo_c.z() > 0 ? plain.pdf(wo_c, wi_c) : 0.0f;
        ASSERT_NEAR(tilted.pdf(wo, wi), pdf, 1e-4f * pdf + 1e-6f) << rc << " " << theta << " " << k;
      }
      double chi2 = 0;
      EXPECT_LT(
          chi2_score(
              tilted, wo, [&](const Vec3f& wi) { return ggx::reflection_pdf(wo_c, coat_frame.to_local(wi), rc * rc); },
              &chi2),
          4.0)
          << "rc " << rc << " theta " << theta << " chi2 " << chi2;
    }
}

// A smooth coat is Cycles's mirror: it reflects ¼·c·F_d(cos θ, 1.5) (Fresnel's equations; G ≈ 1
// at α = 10⁻³), e.g. 0.01 head-on for c = 1.
TEST(BsdfTest, SmoothClearCoatReflectsAQuarterOfFresnel) {
  for (float theta : {0.0f, 45.0f, 75.0f}) {
    const double expected = 0.25 * 0.8 * fresnel_dielectric(std::cos(float(deg_to_rad(theta))), 1.5f);
    EXPECT_NEAR(albedo(coat_only(0.8f, 0.0f), theta), expected, 2e-3 * expected) << theta;
  }
}

// With a diffuse base, the model's sampled albedo is the mean of Cycles's estimator: ∫ q(ωi)
// f(ωi) cos θ_i / pdf(ωi) dω, q the density the samples come from (p_c × GGX's visible normals +
// p_d × cos/π, p the lobes' odds) and pdf the one reported, by quadrature. The coat adds its f to
// the rest (Cycles adds its lobes).
TEST(BsdfTest, ClearCoatSamplingIsCyclesEstimatorAndAdds) {
  for (float rc : {0.3f, 0.6f})
    for (float theta : {0.0f, 70.0f}) {
      PrincipledParams p;
      p.base = Rgb(0.6f, 0.4f, 0.2f), p.specular = 0.0f, p.roughness = 0.5f;
      p.clearcoat = 1.0f, p.clearcoat_roughness = rc;
      const Bsdf b = Bsdf::principled(p);
      const Vec3f wo = direction_at(theta);
      const double w_c = 0.25 * fresnel_dielectric(wo.z(), 1.5f), w_d = p.base.mean();
      const double p_c = w_c / (w_c + w_d);
      const Mc by_sampling = sampled_albedo(b, wo, 400000, 3);
      const Mc by_quadrature = hemisphere_integral(
          [&](const Vec3f& wi) {
            const double q = p_c * ggx::reflection_pdf(wo, wi, rc * rc) + (1 - p_c) * wi.z() / kPi;
            return q * b.eval(wo, wi)[1] * wi.z() / b.pdf(wo, wi);
          },
          400000, 4);
      EXPECT_NEAR(by_sampling.mean, by_quadrature.mean, 4 * std::hypot(by_sampling.se, by_quadrature.se))
          << "rc " << rc << " theta " << theta;
      PrincipledParams bare = p;
      bare.clearcoat = 0;
      const Bsdf without = Bsdf::principled(bare), coat = coat_only(1.0f, rc);
      for (float t : {5.0f, 40.0f, -60.0f}) {
        const Vec3f wi = direction_at(t);
        EXPECT_TRUE(b.eval(wo, wi).isApprox(without.eval(wo, wi) + coat.eval(wo, wi), 1e-5f)) << rc << " " << t;
      }
    }
}

}  // namespace
}  // namespace insitu

namespace insitu {
namespace {

// The velvet distribution is normalized: 2π ∫₀¹ D(μ) μ dμ = 1 (velvet.h derives it).
TEST(BsdfTest, VelvetIsNormalized) {
  for (float sigma : {0.05f, 0.3f, 1.0f})
    EXPECT_NEAR(projected_area([&](float mu) { return velvet::d(mu, sigma); }), 1.0, 2e-3) << sigma;
}

// Sheen alone (a black base without specular) and on a base: samples follow pdf() (uniform for the
// velvet lobe) and their mean weight is ∫ f cos dω by quadrature; the sheen adds its f. Under the
// sanitizers 20× fewer samples (the bounds are the estimates' own standard errors).
TEST(BsdfTest, SheenSamplingMatchesEvalAndPdf) {
  const int n = test::kUnderAsan ? 20000 : 400000;
  for (float rough : {0.3f, 0.8f})
    for (float theta : {0.0f, 60.0f, 85.0f})
      for (float base : {0.0f, 0.5f}) {
        PrincipledParams p;
        p.base = Rgb::Constant(base), p.specular = 0.0f, p.sheen = Rgb(0.8f, 0.6f, 0.4f), p.sheen_roughness = rough;
        const Bsdf b = Bsdf::principled(p);
        const Vec3f wo = direction_at(theta);
        const Mc by_sampling = sampled_albedo(b, wo, n, 3);
        const Mc by_quadrature =
            hemisphere_integral([&](const Vec3f& wi) { return double(b.eval(wo, wi)[1]) * wi.z(); }, n, 4);
        EXPECT_NEAR(by_sampling.mean, by_quadrature.mean, 4 * std::hypot(by_sampling.se, by_quadrature.se))
            << "roughness " << rough << " theta " << theta << " base " << base;
        const Mc pdf_integral = hemisphere_integral([&](const Vec3f& wi) { return double(b.pdf(wo, wi)); }, n, 5);
        EXPECT_NEAR(pdf_integral.mean, 1.0, 4 * pdf_integral.se + 1e-3);
        PrincipledParams bare = p;
        bare.sheen = Rgb::Zero();
        const Vec3f wi = direction_at(-50);
        EXPECT_NEAR(b.eval(wo, wi)[1], Bsdf::principled(bare).eval(wo, wi)[1] + 0.6f * velvet::f(wo, wi, rough), 1e-5f);
      }
}

// Bump shadowing on a Lambertian lobe whose smooth normal is tilted 60° toward +x from the shading
// normal: g = (n_s·ωi) / ((n·ωi)(n_s·n)) is 1 along the shading normal (nothing taken), 0 at
// ωi ⟂ n_s and beyond (all taken); at ωi turned by t toward −x, where cos(t + 60°) = ¼ cos t
// (tan t = (cos 60° − ¼) / sin 60°), g = ½ and G = −⅛ + ¼ + ½ = 0.625.
TEST(BsdfTest, BumpShadowingDimsTheDiffuseTowardTheTerminator) {
  Bsdf b(Rgb::Constant(0.5f), Rgb::Zero(), 1.0f);
  const float beta = 60 * kPiF / 180;
  const Vec3f wo(0, 0, 1), ns(std::sin(beta), 0, std::cos(beta));
  const Rgb plain = b.eval(wo, wo);
  b.set_smooth_normal(ns);
  EXPECT_TRUE(b.eval(wo, wo).isApprox(plain));
  const float t = std::atan((std::cos(beta) - 0.25f) / std::sin(beta));  // cos(t + β) = ¼ cos t
  const Vec3f half(-std::sin(t), 0, std::cos(t));
  EXPECT_NEAR(b.eval(wo, half)[0] / plain[0], 0.625f, 1e-4f);
  const Vec3f beyond = Vec3f(-std::cos(beta), 0, std::sin(beta) - 0.01f).normalized();  // n_s·ωi < 0 < n·ωi
  EXPECT_EQ(b.eval(wo, beyond)[0], 0.0f);
}

}  // namespace
}  // namespace insitu
