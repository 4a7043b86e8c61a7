// The surface models of the objects, in a local frame with the normal along +z.
//
// `obj` (OBJ's MTL): Lambertian diffuse plus a glossy GGX lobe.
//   f(ωo, ωi) = (1 − F(ωo·n))·ρ_d/π  +  D(h) G(ωo, ωi) F(ωi·h) / (4 |ωo·n| |ωi·n|)
// ρ_d = Kd × map_Kd; the specular reflectance at normal incidence F0 = Ks (Schlick's Fresnel,
// F = F0 + (1 − F0)(1 − cos)^5); roughness α = √(2/(Ns + 2)), Walter et al. 2007's match of a
// Phong exponent to a microfacet width. The diffuse term is weighted by what the specular Fresnel
// reflection leaves, so the total never reflects more than arrives (BsdfTest.EnergyIsConserved).
// With Ks = 0 the model is exactly Lambertian.
//
// `principled` (glTF): Cycles 3.4's Principled BSDF, lobe by lobe as its
// kernel sets it up (intern/cycles/kernel/svm/closure.h, CLOSURE_BSDF_PRINCIPLED_ID), for the
// parameters insitu reads (no subsurface, no anisotropy), with the Velvet BSDF that Blender's
// glTF importer adds for sheen:
//   diffuse   base·(1 − m)(1 − t) · f_pd, the principled diffuse of bsdf_principled_diffuse.h:
//             f_pd = 1/π [(1 − ½F_V)(1 − ½F_L) + R (F_L + F_V + F_L F_V (R − 1))],
//             F_x = (1 − cos θ_x)^5, R = r (1 + ωo·ωi)  (Burley 2012's retro-reflection);
//   specular  (1 − T) × GGX, α = r², single-scattering (the node's "GGX" distribution), with Cycles's
//             interpolated Fresnel (bsdf_util.h, interpolate_fresnel_color):
//             F = c0 (1 − F_H) + F_H,  F_H = (F_d(ωi·h, η) − F0) / (1 − F0),
//             c0 = 0.08·s·(1 − m) + base·m,  F0 = 0.08·s,  η = 2/(1 − √(0.08·s)) − 1,
//             F_d the dielectric Fresnel reflectance (fresnel_dielectric_cos).
//   clear coat ¼·c · F_d(ωi·h, 1.5) D₁(h) G1(ωo) G1(ωi) / (4 |ωo·n| |ωi·n|), D₁ GTR1 of
//             α = r_c² (render/gtr1.h), G1 GGX's Smith term at a fixed α = 0.25
//             (bsdf_microfacet.h, CLOSURE_BSDF_MICROFACET_GGX_CLEARCOAT_ID); where Cycles makes
//             the coat a mirror (α² ≤ 10⁻⁷), GGX at α = 10⁻³;
//   sheen     sheen colour × the Ashikhmin velvet lobe of σ = sheen roughness (render/velvet.h),
//             added (KHR_materials_sheen as Blender 3.4 imports it: a Velvet BSDF through an Add
//             Shader, not the Principled BSDF's own sheen).
//   glass     T = t·(1 − m), two closures of α = r² and the index η (1/η from inside, on a back
//             face), their Fresnel F = F_d(ωo·n, η) taken once at the macroscopic normal:
//             reflection  T·F × GGX reflection with a microfacet Fresnel of 1;
//             refraction  base·T·max(10⁻⁴, 1 − F) × Walter et al. 2007's GGX refraction without
//             Fresnel, ωi on the other side (a direction with ωi·n < 0), evaluated as Cycles
//             evaluates it, also where no microfacet refracts (render/ggx.h, cycles_refraction).
// m: metallic, r: roughness, s: specular, c: clear coat, r_c: its roughness, t: transmission. Cycles adds the
// lobes: none is weighted by what another reflects, so a white base reflects up to ~1.5 × what
// arrives at grazing angles (BsdfTest.PrincipledGainsWhatCyclesGains); each lobe alone conserves
// energy.
//
// Sampling: the specular lobe by GGX's visible normals (render/ggx.h), the diffuse one
// cosine-weighted; the lobe with probability: obj, p_s = max F(ωo·n) clamped to [0.05, 0.95];
// principled, Cycles's sample weights, each lobe's w over their sum: w_s the mean of F at ωo·n,
// w_c = ¼·c·F_d(ωo·n, 1.5), w_d the mean diffuse weight, w_v the mean sheen colour (its lobe
// sampled uniformly, as Cycles does), the glass's T·F and mean(base)·T·(1 − F); a refraction
// through a visible normal under total internal reflection is no sample, as in Cycles. pdf() is the
// mixture. A mirror (Cycles's singular lobes, α² ≤ 10⁻⁷) is GGX at α = 10⁻³ here, for the
// specular lobe, the coat and the glass alike.
//
// The clear coat is sampled as Cycles 3.4 samples it (bsdf_microfacet_ggx_sample): directions from
// GGX's visible normals at α_c, their density reported as Cycles reports it,
// G1(ωo; 0.25) D₁(h) / (4 |ωo·n|), which is GTR1's, not theirs. The estimator is Cycles's, and so is
// its mean: where the BSDF's samples carry a path (a glossy coat's highlight), the coat is GGX-sharp
// with weight ¼·c·F·G1(ωi; 0.25) per sample; where the light's samples do (the coat's wide tails),
// it is GTR1. Drawing from D₁ itself, as consistency would ask, blurred a lacquer's reflections of
// the windows against Cycles's by 8 % (docs/materials.md, "The coat's samples").
#pragma once
#include "core/math.h"
#include "core/sampling.h"
#include "render/texture.h"

namespace insitu {

struct Material;

// The principled model's parameters (Cycles's Principled BSDF inputs of the same names).
struct PrincipledParams {
  Rgb base = Rgb::Constant(0.8f);
  float metallic = 0.0f, roughness = 0.5f, specular = 0.5f;
  float clearcoat = 0.0f, clearcoat_roughness = 0.03f;
  Rgb sheen = Rgb::Zero();  // the Velvet BSDF's colour (KHR_materials_sheen's sheenColor)
  float sheen_roughness = 0.0f;
  float transmission = 0.0f, ior = 1.5f;
  bool inside = false;         // seen from inside (a back face): the glass's index is 1/ior
  float specular_tint = 0.0f;  // the dielectric's F0 tinted toward the base colour's hue
};

struct BsdfSample {
  Vec3f wi;    // local
  Rgb weight;  // f·cos θ_i / pdf
  float pdf = 0;
};

class Bsdf {
 public:
  // The obj model.
  Bsdf(const Rgb& diffuse, const Rgb& f0, float alpha);
  // The principled model; parameters clamped to [0, 1].
  static Bsdf principled(const PrincipledParams& p);
  static Bsdf principled(const Rgb& base, float metallic, float roughness, float specular) {
    return principled(PrincipledParams{base, metallic, roughness, specular});
  }
  // The material's model at a surface point, its textures sampled there; `inside`: met from
  // behind its face (the glass's index inverted).
  static Bsdf from_material(const Material& m, const UvSets& uv, bool inside = false);

  // f, local directions, ωo above; ωi below (ωi.z < 0) is the glass's refraction, 0 without it.
  Rgb eval(const Vec3f& wo, const Vec3f& wi) const;
  float pdf(const Vec3f& wo, const Vec3f& wi) const;  // solid-angle density of sample()
  // A direction and its weight f |cos θi| / pdf; below the surface for a refraction.
  bool sample(const Vec3f& wo, float u_lobe, float u1, float u2, BsdfSample* out) const;
  bool glossy() const { return glossy_; }
  bool transmits() const { return glass_ > 0; }
  // Cycles's bump shadowing of its diffuse closures (kernel/closure/bsdf.h, bump_shadowing_term;
  // Chiang, Li and Burley 2019, "Taming the Shadow Terminator"), for a shading normal (this BSDF's
  // +z) bent away from the smooth one by a normal map or a valid-reflection bend: the diffuse lobe
  // is multiplied by G(g) = −g³ + g² + g for g = (n_s·ωi) / ((n·ωi)(n_s·n)) in [0, 1), 1 above, 0
  // below. `n_smooth` is the smooth normal in this BSDF's frame.
  void set_smooth_normal(const Vec3f& n_smooth) {
    smooth_n_ = n_smooth;
    bump_ = true;
  }
  // The clear coat's own normal in this BSDF's frame, where it is not +z: Cycles's Clearcoat Normal,
  // which glTF's importer leaves unconnected, so that the coat keeps the smooth normal (bent to a
  // valid reflection) while a normal map bends the other lobes, as KHR_materials_clearcoat asks.
  // The coat is evaluated, weighed and sampled about it; a coat direction below +z is no sample,
  // as for every lobe but the refraction.
  void set_coat_normal(const Vec3f& n_coat) {
    coat_frame_ = Frame(n_coat);
    coat_tilted_ = true;
  }

 private:
  Bsdf() = default;
  Rgb fresnel(float cos_ih) const;                      // the specular lobe's F at ωi·h
  Rgb diffuse(const Vec3f& wo, const Vec3f& wi) const;  // the diffuse lobe's f
  Rgb coat(const Vec3f& wo, const Vec3f& wi) const;     // the clear coat's f
  float bump_shadowing(const Vec3f& wi) const;
  float coat_pdf(const Vec3f& wo, const Vec3f& wi) const;
  Rgb glass(const Vec3f& wo, const Vec3f& wi) const;  // the glass's reflection or refraction f
  struct LobeOdds {
    float specular = 0, coat = 0, sheen = 0, reflect = 0, refract = 0;  // the rest: diffuse
    float others() const { return specular + coat + sheen + reflect + refract; }
  };
  LobeOdds lobe_odds(const Vec3f& wo) const;
  Vec3f to_coat(const Vec3f& w) const { return coat_tilted_ ? coat_frame_.to_local(w) : w; }
  float mixture_pdf(const LobeOdds& odds, const Vec3f& wo, const Vec3f& wi) const;
  bool principled_ = false;
  Rgb diffuse_ = Rgb::Zero(), f0_ = Rgb::Zero();  // principled: base·(1 − m) and c0
  float alpha_ = 1.0f;
  bool glossy_ = false;
  float roughness_ = 0.0f, eta_ = 1.5f, f0_dielectric_ = 0.04f;  // principled only
  float coat_ = 0.0f, coat_alpha_ = 1.0f;                        // ¼·c, α_c
  bool coat_ggx_ = false;                                        // a mirror coat: GGX at α = 10⁻³
  bool coat_tilted_ = false;                                     // the coat about coat_frame_'s normal
  Frame coat_frame_{Vec3f::UnitZ()};
  Rgb sheen_ = Rgb::Zero();  // the velvet lobe's colour
  float sheen_sigma_ = 1.0f;
  float specular_weight_ = 1.0f;                                // 1 − T
  float glass_ = 0.0f, glass_alpha_ = 1.0f, glass_eta_ = 1.5f;  // T, α, η from ωo's side
  Rgb glass_tint_ = Rgb::Ones();                                // the base colour
  bool bump_ = false;
  Vec3f smooth_n_ = Vec3f::UnitZ();
};

// The reflectance of a smooth dielectric of relative index η at cos θ (Cycles's
// fresnel_dielectric_cos; 1 under total internal reflection).
float fresnel_dielectric(float cos_theta, float eta);

}  // namespace insitu
