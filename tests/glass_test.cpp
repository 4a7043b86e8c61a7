// Glass (render/bsdf.h): Cycles 3.4's Principled BSDF with transmission, its two closures (a
// reflection of weight T·F and a refraction of weight base·T·(1 − F), GGX, Walter et al. 2007),
// their sampling against their pdf, and the path integrator through a glass slab (refraction,
// internal reflections, Volume Absorption) against the series a slab sums to.
#include <gtest/gtest.h>

#include <cmath>

#include "box_fixture.h"
#include "core/sampler.h"
#include "cube_fixture.h"
#include "gltf_fixture.h"
#include "integrators/registry.h"
#include "render/bsdf.h"
#include "render/ggx.h"
#include "render/gltf_mesh.h"
#include "bsdf_sampling.h"
#include "chi2.h"
#include "test_util.h"

namespace insitu {
namespace {

Vec3f glass_wo(float theta_deg) {
  const float t = float(deg_to_rad(theta_deg));
  return {std::sin(t), 0.0f, std::cos(t)};
}

Bsdf glass_bsdf(const Rgb& base, float roughness, float transmission = 1.0f, bool inside = false) {
  PrincipledParams p;
  p.base = base, p.metallic = 0, p.roughness = roughness, p.specular = 0.5f;
  p.transmission = transmission, p.ior = 1.5f, p.inside = inside;
  return Bsdf::principled(p);
}

struct GlassMc {
  double mean, se;
};

// E[f |cos θi| / pdf] over the BSDF's own samples, green channel (failed samples count 0).
GlassMc glass_albedo(const Bsdf& b, const Vec3f& wo, int count, int channel = 1) {
  double sum = 0, sum2 = 0;
  for (int k = 0; k < count; ++k) {
    Sampler s(31, std::uint64_t(k), 0);
    BsdfSample bs;
    const float ul = s.next(), u1 = s.next(), u2 = s.next();
    const double x = b.sample(wo, ul, u1, u2, &bs) ? double(bs.weight[channel]) : 0.0;
    sum += x, sum2 += x * x;
  }
  const double m = sum / count;
  return {m, std::sqrt(std::max(0.0, sum2 / count - m * m) / count)};
}

// ∫ g(ωi) dω over the whole sphere by uniform sampling (pdf 1/4π).
template <class G>
GlassMc sphere_integral(G g, int count, std::uint64_t seed) {
  double sum = 0, sum2 = 0;
  for (int k = 0; k < count; ++k) {
    Sampler s(seed, std::uint64_t(k), 0);
    const float z = 2 * s.next() - 1, phi = 2 * kPiF * s.next(), r = std::sqrt(std::max(0.0f, 1 - z * z));
    const double x = 4 * kPi * g(Vec3f(r * std::cos(phi), r * std::sin(phi), z));
    sum += x, sum2 += x * x;
  }
  const double m = sum / count;
  return {m, std::sqrt(std::max(0.0, sum2 / count - m * m) / count)};
}

// A smooth glass refracts by Snell's law, from outside (η = 1.5) and from inside (1/1.5), into
// the direction opposite the reflection's side.
TEST(Glass, SmoothGlassRefractsBySnellsLaw) {
  for (bool inside : {false, true}) {
    const float eta = inside ? 1 / 1.5f : 1.5f;
    const Bsdf b = glass_bsdf(Rgb::Ones(), 0.0f, 1.0f, inside);
    for (float theta : {0.0f, 20.0f, 40.0f}) {
      const Vec3f wo = glass_wo(theta);
      BsdfSample bs;
      ASSERT_TRUE(b.sample(wo, 0.999f, 0.3f, 0.6f, &bs)) << theta;
      ASSERT_LT(bs.wi.z(), 0) << theta;
      const float sin_t = std::sqrt(bs.wi.x() * bs.wi.x() + bs.wi.y() * bs.wi.y());
      EXPECT_NEAR(sin_t, std::sin(float(deg_to_rad(theta))) / eta, 3e-3f) << "inside " << inside << " " << theta;
      if (theta > 0) {
        EXPECT_LT(bs.wi.x(), 0) << theta;
      }
    }
  }
}

// Lossless: a smooth white glass reflects F and transmits 1 − F, which sum to 1 at every angle,
// from outside and from inside (where beyond the critical angle, 41.8°, all of it reflects). A
// tinted one seen head-on returns F + base (1 − F): the reflection is white, the refraction tinted.
TEST(Glass, SmoothWhiteGlassIsLossless) {
  for (bool inside : {false, true})
    for (float theta : {0.0f, 30.0f, 60.0f, 80.0f}) {
      const GlassMc a = glass_albedo(glass_bsdf(Rgb::Ones(), 0.0f, 1.0f, inside), glass_wo(theta), 100000);
      EXPECT_NEAR(a.mean, 1.0, 2e-3) << "inside " << inside << " theta " << theta;
    }
  const Rgb base(0.5f, 0.7f, 0.9f);
  const float F = fresnel_dielectric(1.0f, 1.5f);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(glass_albedo(glass_bsdf(base, 0.0f), glass_wo(0), 100000, c).mean, F + base[c] * (1 - F), 3e-3) << c;
}

// Whether a microfacet refracts ωo into ωi (ωi below): where none does, Cycles's evaluation of
// the refraction lobe is not 0 (render/ggx.h, cycles_refraction), and its sampler never goes.
bool refractable(const Vec3f& wo, const Vec3f& wi, bool inside) {
  Vec3f h;
  return wi.z() >= 0 || ggx::refraction_half(wo, wi, inside ? 1 / 1.5f : 1.5f, &h);
}

// An index of 1 (glTF's least) passes the light straight through and reflects none, from outside
// and inside. Smooth, all of it; rough, what GGX's masking of the way out lets through, G1(ωi) at
// ωi = −ωo (Cycles, which passes an index within 10⁻⁴ of 1 straight through, gives 1 there, and
// G1 at 1.001, the index insitu takes for 1).
TEST(Glass, AnIndexOfOneIsInvisible) {
  for (bool inside : {false, true})
    for (float roughness : {0.0f, 0.5f}) {
      PrincipledParams p;
      p.base = Rgb::Ones(), p.metallic = 0, p.roughness = roughness, p.transmission = 1, p.ior = 1, p.inside = inside;
      const Bsdf b = Bsdf::principled(p);
      const Vec3f wo = glass_wo(50);
      const float alpha = std::max(1e-3f, roughness * roughness);
      EXPECT_NEAR(glass_albedo(b, wo, 20000).mean, ggx::g1(wo.z(), alpha), 2e-3)
          << "inside " << inside << " roughness " << roughness;
      BsdfSample bs;
      ASSERT_TRUE(b.sample(wo, 0.5f, 0.3f, 0.8f, &bs));
      EXPECT_LT((bs.wi + wo).norm(), 2e-2f) << "inside " << inside << " roughness " << roughness;
    }
}

// Rough glass's sampled weights average to ∫ f |cos| dω over the directions it can sample
// (computed by uniform sampling of the sphere), for glass alone and half glass over a diffuse
// base, from outside and inside; ∫ pdf dω over them is the fraction of samples that succeed
// (refractions under total internal reflection fail).
TEST(Glass, RoughGlassSamplingMatchesEvalAndPdf) {
  for (bool inside : {false, true})
    for (float transmission : {1.0f, 0.5f})
      for (float theta : {10.0f, 60.0f}) {
        const Bsdf b = glass_bsdf(Rgb(0.9f, 0.8f, 0.6f), 0.4f, transmission, inside);
        const Vec3f wo = glass_wo(theta);
        const GlassMc by_sampling = glass_albedo(b, wo, 400000);
        const GlassMc by_quadrature = sphere_integral(
            [&](const Vec3f& wi) {
              return refractable(wo, wi, inside) ? double(b.eval(wo, wi)[1]) * std::abs(wi.z()) : 0.0;
            },
            800000, 4);
        EXPECT_NEAR(by_sampling.mean, by_quadrature.mean, 4 * std::hypot(by_sampling.se, by_quadrature.se))
            << "inside " << inside << " transmission " << transmission << " theta " << theta;
        const GlassMc pdf_integral = sphere_integral(
            [&](const Vec3f& wi) { return refractable(wo, wi, inside) ? double(b.pdf(wo, wi)) : 0.0; }, 800000, 5);
        const test::Fraction ok = test::success_fraction(b, wo);
        EXPECT_NEAR(pdf_integral.mean, ok.p, 4 * std::hypot(pdf_integral.se, ok.se) + 1e-3)
            << "inside " << inside << " transmission " << transmission << " theta " << theta;
      }
}

// Cycles evaluates the refraction lobe where no microfacet refracts ωo into ωi (seen head-on, a
// direction 60° from the inward normal: Snell's law reaches only 48° for a microfacet that still
// faces ωo), with a density its sampler does not have there; its light samples add that light.
// insitu evaluates as Cycles does; where a microfacet does refract, the two densities agree.
TEST(Glass, RefractionIsEvaluatedAsCyclesEvaluatesIt) {
  const float alpha = 0.25f, eta = 1.5f;
  const Vec3f wo(0, 0, 1), beyond = -glass_wo(-60), within = -glass_wo(-20);
  float pdf = 0;
  EXPECT_GT(ggx::cycles_refraction(wo, beyond, alpha, eta, &pdf), 0.0f);
  EXPECT_GT(pdf, 0.0f);
  EXPECT_EQ(ggx::refraction_pdf(wo, beyond, alpha, eta), 0.0f);
  ggx::cycles_refraction(wo, within, alpha, eta, &pdf);
  EXPECT_NEAR(pdf, ggx::refraction_pdf(wo, within, alpha, eta), 1e-5f * pdf);
  EXPECT_GT(pdf, 0.0f);
}

// The χ² score of rough glass's samples against pdf() where they can go, over (cos θ ∈ [−1, 1], φ)
// bins.
double glass_chi2(const Bsdf& b, const Vec3f& wo, bool inside) {
  constexpr int kTheta = 32, kPhi = 32, kN = 400000, kSub = 24;
  std::vector<double> observed(kTheta * kPhi, 0.0), expected(kTheta * kPhi, 0.0);
  for (int k = 0; k < kN; ++k) {
    Sampler s(41, std::uint64_t(k), 0);
    BsdfSample bs;
    const float ul = s.next(), u1 = s.next(), u2 = s.next();
    if (!b.sample(wo, ul, u1, u2, &bs)) continue;
    const int i = std::clamp(int((bs.wi.z() + 1) / 2 * kTheta), 0, kTheta - 1);
    const float phi = std::atan2(bs.wi.y(), bs.wi.x()) + kPiF;
    observed[std::size_t(i * kPhi + std::clamp(int(phi / (2 * kPiF) * kPhi), 0, kPhi - 1))] += 1;
  }
  for (int i = 0; i < kTheta; ++i)
    for (int j = 0; j < kPhi; ++j)
      for (int a = 0; a < kSub; ++a)
        for (int c = 0; c < kSub; ++c) {
          const float z = -1 + 2 * (float(i) + (float(a) + 0.5f) / kSub) / kTheta;
          const float phi = (float(j) + (float(c) + 0.5f) / kSub) / kPhi * 2 * kPiF - kPiF;
          const float r = std::sqrt(std::max(0.0f, 1 - z * z));
          const double d_omega = (2.0 / kTheta) * (2 * kPi / kPhi) / (kSub * kSub);
          const Vec3f wi(r * std::cos(phi), r * std::sin(phi), z);
          if (refractable(wo, wi, inside)) expected[std::size_t(i * kPhi + j)] += kN * b.pdf(wo, wi) * d_omega;
        }
  return test::chi2_score_of(observed, expected);
}

TEST(Glass, RoughGlassSamplesFollowTheirPdf) {
  for (bool inside : {false, true})
    for (float roughness : {0.3f, 0.7f})
      for (float theta : {15.0f, 70.0f})
        EXPECT_LT(glass_chi2(glass_bsdf(Rgb::Ones(), roughness, 1.0f, inside), glass_wo(theta), inside), 4.0)
            << "inside " << inside << " roughness " << roughness << " theta " << theta;
}

// Seen head-on through a wide smooth slab of thickness d in a constant white environment, the
// path integrator sums the slab's series: what the front face reflects, F, what it lets in and
// the back face's reflections send back, and what comes through, each crossing absorbed by
// e = exp(−σ_a d):
//   L = F + (1 − F)² F e² / (1 − F² e²) + (1 − F)² e / (1 − F² e²),
// which is 1 without absorption (a lossless glass in a white furnace).
TEST(Glass, ASlabSumsItsSeries) {
  test::TempDir dir;
  const float d = 0.1f;
  EmbreeScene clear_box = test::make_box(dir, "1 1 1", 1.0);
  std::vector<Mesh> meshes = clear_box.meshes();
  transform_mesh(meshes[0], object_transform(Vec3d::Zero(), 0, {0, 1, 0}, Vec3d(50, 50, d / 2)));
  Material& glass = meshes[0].materials[0];
  glass.principled = true, glass.kd = Rgb::Ones(), glass.metallic = 0, glass.roughness = 0, glass.specular = 0.5f;
  glass.transmission = 1, glass.ior = 1.5f;
  const Rgb sigma_a(0.0f, 2.0f, 8.0f);  // 1/m
  glass.absorption = sigma_a;
  const EmbreeScene slab(std::move(meshes));
  const CubeMap env = test::constant_cube(8, Rgb::Ones());
  RenderInputs in;
  in.objects = &slab;
  in.environment = &env;
  const auto path = make_integrator("path", in, json{{"max_depth", 12}});
  const Ray ray{Vec3f(0, 0, 5), Vec3f(0, 0, -1)};
  const double F = fresnel_dielectric(1.0f, 1.5f);
  for (int c = 0; c < 3; ++c) {
    const double e = std::exp(-double(sigma_a[c]) * d), q = 1 - F * F * e * e;
    const double expected = F + (1 - F) * (1 - F) * F * e * e / q + (1 - F) * (1 - F) * e / q;
    double sum = 0, sum2 = 0;
    const int n = 4000;
    for (int k = 0; k < n; ++k) {
      Sampler s(7, 0, std::uint64_t(k));
      const double x = path->sample(ray, s).radiance[c];
      sum += x, sum2 += x * x;
    }
    const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, expected, 4 * se + 2e-3) << "channel " << c;
  }
}

// KHR_materials_transmission, _ior and _volume as Blender 3.4's importer reads them: the
// Principled BSDF's transmission and IOR, and a Volume Absorption of density 1/attenuationDistance
// and colour attenuationColor, σ_a = (1 − colour)/distance, where the volume has a thickness.
TEST(Glass, TheGltfExtensionsAreRead) {
  test::TempDir dir;
  const json glass = {
      {"pbrMetallicRoughness", {{"roughnessFactor", 0.1}}},
      {"extensions",
       {{"KHR_materials_transmission", {{"transmissionFactor", 0.9}}},
        {"KHR_materials_ior", {{"ior", 1.45}}},
        {"KHR_materials_volume",
         {{"thicknessFactor", 0.02}, {"attenuationDistance", 0.5}, {"attenuationColor", {0.9, 0.5, 0.25}}}}}}};
  Warnings w;
  const Mesh m = load_mesh(test::write_gltf_sphere(dir, "glass", Vec3f::Zero(), 0.5f, glass, 8), w);
  EXPECT_TRUE(w.items.empty()) << (w.items.empty() ? "" : w.items[0]);
  const Material& g = m.materials[0];
  EXPECT_FLOAT_EQ(g.transmission, 0.9f);
  EXPECT_FLOAT_EQ(g.ior, 1.45f);
  EXPECT_TRUE(g.absorption.isApprox(Rgb(0.2f, 1.0f, 1.5f), 1e-6f)) << g.absorption.transpose();
  // A thin-walled volume (no thickness) absorbs nothing, as Blender adds no volume for it; an
  // index below 1 is refused with its JSON path.
  json thin = glass;
  thin["extensions"]["KHR_materials_volume"]["thicknessFactor"] = 0.0;
  EXPECT_TRUE(load_mesh(test::write_gltf_sphere(dir, "thin", Vec3f::Zero(), 0.5f, thin, 8), w)
                  .materials[0]
                  .absorption.isZero());
  json low = glass;
  low["extensions"]["KHR_materials_ior"]["ior"] = 0.8;
  try {
    load_mesh(test::write_gltf_sphere(dir, "low", Vec3f::Zero(), 0.5f, low, 8), w);
    ADD_FAILURE() << "an ior of 0.8 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("low.gltf: $.materials[0].extensions.KHR_materials_ior.ior: must be within"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace insitu
