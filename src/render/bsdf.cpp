#include "render/bsdf.h"

#include <algorithm>

#include "render/ggx.h"
#include "render/gtr1.h"
#include "render/velvet.h"
#include "render/mesh.h"

namespace insitu {

namespace {

// Schlick's weight (1 − cos θ)^5.
float schlick_weight(float cos_theta) {
  const float m = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
  return m * m * m * m * m;
}

Rgb schlick(const Rgb& f0, float cos_theta) { return f0 + (Rgb::Ones() - f0) * schlick_weight(cos_theta); }

// Cycles drops a closure whose weight is below CLOSURE_WEIGHT_CUTOFF.
constexpr float kWeightCutoff = 1e-5f;
// A glass index within this of 1 is taken as 1 + it (Bsdf::principled).
constexpr float kIndexMatched = 1e-3f;
// Specular's ceiling: F0 = 0.08·s stays below 1 (Cycles's ior = 2/(1 − √F0) − 1).
constexpr float kMaxSpecular = 12.4f;
// The clear coat: index of refraction 1.5, Smith masking at a fixed α (Disney 2012); a mirror
// where α² ≤ 10⁻⁷ (bsdf_microfacet.h: "alpha_x * alpha_y <= 1e-7f").
constexpr float kCoatEta = 1.5f, kCoatMaskingAlpha = 0.25f, kCoatMirrorAlpha2 = 1e-7f, kMirrorAlpha = 1e-3f;

}  // namespace

// Fresnel's equations for unpolarized light, without the refracted direction:
// g = √(η² − 1 + c²), R = ½ ((g − c)/(g + c))² (1 + ((c (g + c) − 1)/(c (g − c) + 1))²).
float fresnel_dielectric(float cos_theta, float eta) {
  const float c = std::abs(cos_theta);
  float g = eta * eta - 1 + c * c;
  if (g <= 0) return 1.0f;
  g = std::sqrt(g);
  const float a = (g - c) / (g + c), b = (c * (g + c) - 1) / (c * (g - c) + 1);
  return 0.5f * a * a * (1 + b * b);
}

Bsdf::Bsdf(const Rgb& diffuse, const Rgb& f0, float alpha)
    : diffuse_(diffuse),
      f0_(f0.max(0.0f).min(1.0f)),
      alpha_(std::clamp(alpha, 1e-3f, 1.0f)),
      glossy_(f0.maxCoeff() > 0) {}

Bsdf Bsdf::principled(const PrincipledParams& p) {
  const Rgb base = p.base.max(0.0f);
  const float m = std::clamp(p.metallic, 0.0f, 1.0f), r = std::clamp(p.roughness, 0.0f, 1.0f);
  // Specular may exceed 1 (F0 up to 0.08·s; Blender's importer gives s > 1 for an index above 1.5).
  const float s = std::clamp(p.specular, 0.0f, kMaxSpecular), c = std::clamp(p.clearcoat, 0.0f, 1.0f);
  const float rc = std::clamp(p.clearcoat_roughness, 0.0f, 1.0f);
  const float t = std::clamp(p.transmission, 0.0f, 1.0f), T = t * (1 - m);
  Bsdf b;
  b.principled_ = true;
  b.diffuse_ = base * ((1 - m) * (1 - t));
  b.specular_weight_ = s > kWeightCutoff || m > kWeightCutoff ? 1 - T : 0.0f;
  if (b.specular_weight_ <= kWeightCutoff) b.specular_weight_ = 0;
  // Cycles (svm/closure.h): F0 = 0.08 s · (1 − st + st · base / lum(base)) (1 − m) + base · m,
  // lum = 0.3 R + 0.6 G + 0.1 B (the hue of the base, 1 for black), each channel within [0, 1].
  const float st = std::clamp(p.specular_tint, 0.0f, 1.0f);
  const float lum = cycles_tint_luminance(base);
  const Rgb tint = Rgb::Constant(1 - st) + (lum > 0 ? Rgb(base / lum) : Rgb::Ones()) * st;
  b.f0_ = (0.08f * s * tint * (1 - m) + base * m).min(1.0f);
  b.roughness_ = r;
  b.alpha_ = std::max(kMirrorAlpha, r * r);
  b.f0_dielectric_ = std::min(0.08f * s, 0.999f);
  b.eta_ = 2 / (1 - std::sqrt(b.f0_dielectric_)) - 1;
  if (c > kWeightCutoff) {
    b.coat_ = 0.25f * c;
    b.coat_ggx_ = rc * rc * rc * rc <= kCoatMirrorAlpha2;
    b.coat_alpha_ = b.coat_ggx_ ? kMirrorAlpha : rc * rc;
  }
  if (p.sheen.maxCoeff() > kWeightCutoff) {
    b.sheen_ = p.sheen.max(0.0f);
    b.sheen_sigma_ = velvet::sigma(p.sheen_roughness);
  }
  if (T > kWeightCutoff) {
    // Cycles: eta = max(ior, 10⁻⁵), inverted on a back face. An index within 10⁻³ of 1 is 1.001:
    // Cycles passes light straight through an index within 10⁻⁴ of 1 (a singular closure), where
    // the refraction's half vector ωo + η ωi vanishes; at 1.001 a microfacet tilted by θ turns the
    // light by about 0.001 tan θ, and the surface reflects 2·10⁻⁷ of it.
    float eta = std::max(p.ior, 1e-5f);
    if (std::abs(eta - 1) < kIndexMatched) eta = 1 + kIndexMatched;
    b.glass_ = T;
    b.glass_alpha_ = std::max(kMirrorAlpha, r * r);
    b.glass_eta_ = p.inside ? 1 / eta : eta;
    b.glass_tint_ = base;
  }
  b.glossy_ = b.specular_weight_ > 0 || b.coat_ > 0 || b.sheen_.maxCoeff() > 0 || b.glass_ > 0;
  return b;
}

Bsdf Bsdf::from_material(const Material& m, const UvSets& uv, bool inside) {
  const Rgb base = m.base_colour(uv);
  if (m.principled) {
    const Rgb mr = m.map_metallic_roughness.sample(uv);  // glTF: G roughness, B metallic
    const Rgb cc = m.map_clearcoat.sample(uv), ccr = m.map_clearcoat_roughness.sample(uv);  // R, G
    // MTL's grey maps as Cycles converts a colour to a float: its luminance (Rec. 709).
    auto grey = [&](const Texture& t) { return t ? luminance(t.sample(uv)) : 1.0f; };
    const float metallic_map = grey(m.map_metallic), roughness_map = grey(m.map_roughness);
    const float transmission = m.transmission * m.map_transmission.sample(uv)[0];
    PrincipledParams p{base,
                       m.metallic * mr[2] * metallic_map,
                       m.roughness * mr[1] * roughness_map,
                       m.specular_at(uv, transmission),
                       m.clearcoat * cc[0],
                       m.clearcoat_roughness * ccr[1],
                       m.sheen * m.map_sheen.sample(uv),
                       m.sheen_roughness * m.map_sheen_roughness.sample_alpha(uv),
                       transmission,
                       m.ior,
                       inside};
    p.specular_tint = m.specular_tint(base, m.specular_colour_at(uv));
    return principled(p);
  }
  // Walter et al. 2007: α = √(2/(Ns + 2)).
  const float alpha = std::sqrt(2.0f / (std::max(0.0f, m.ns) + 2.0f));
  return Bsdf(base, m.ks, alpha);
}

Rgb Bsdf::fresnel(float cos_ih) const {
  if (!principled_) return schlick(f0_, cos_ih);
  const float f_h = (fresnel_dielectric(cos_ih, eta_) - f0_dielectric_) / (1 - f0_dielectric_);
  return f0_ * (1 - f_h) + f_h;
}

Rgb Bsdf::diffuse(const Vec3f& wo, const Vec3f& wi) const {
  if (!principled_) return glossy_ ? Rgb((Rgb::Ones() - schlick(f0_, wo.z())) * diffuse_ / kPiF) : diffuse_ / kPiF;
  const float fv = schlick_weight(wo.z()), fl = schlick_weight(wi.z());
  const float rr = roughness_ * (1 + wo.dot(wi));
  return diffuse_ * (((1 - 0.5f * fv) * (1 - 0.5f * fl) + rr * (fl + fv + fl * fv * (rr - 1))) / kPiF);
}

Rgb Bsdf::coat(const Vec3f& wo_local, const Vec3f& wi_local) const {
  const Vec3f wo = to_coat(wo_local), wi = to_coat(wi_local);
  const float co = wo.z(), ci = wi.z();
  if (co <= 0 || ci <= 0) return Rgb::Zero();
  const Vec3f h = (wo + wi).normalized();
  const float D = coat_ggx_ ? ggx::d(h.z(), coat_alpha_) : gtr1::d(h.z(), coat_alpha_);
  const float a_g = coat_ggx_ ? coat_alpha_ : kCoatMaskingAlpha;
  const float G = ggx::g1(co, a_g) * ggx::g1(ci, a_g);
  return Rgb::Constant(coat_ * fresnel_dielectric(std::max(0.0f, wi.dot(h)), kCoatEta) * D * G / (4 * co * ci));
}

// The glass: reflection T·F·D G/(4 cos θo cos θi), or refraction base·T·max(10⁻⁴, 1 − F)·f_t,
// F = F_d(ωo·n, η) (closure.h: the Fresnel is taken at the closure's normal, once).
Rgb Bsdf::glass(const Vec3f& wo, const Vec3f& wi) const {
  const float F = fresnel_dielectric(wo.z(), glass_eta_);
  if (wi.z() > 0) {
    const Vec3f h = (wo + wi).normalized();
    const float G = ggx::g1(wo.z(), glass_alpha_) * ggx::g1(wi.z(), glass_alpha_);
    return Rgb::Constant(glass_ * F * ggx::d(h.z(), glass_alpha_) * G / (4 * wo.z() * wi.z()));
  }
  float pdf = 0;
  const float f_cos = ggx::cycles_refraction(wo, wi, glass_alpha_, glass_eta_, &pdf);
  return glass_tint_ * (glass_ * std::max(1e-4f, 1 - F) * f_cos / -wi.z());
}

// Cycles's density for the coat, pdf = G1(ωo; 0.25) D₁(h) / (4 |ωo·n|), which is not the density
// its samples are drawn from (GGX's visible normals at α_c; render/gtr1.h).
float Bsdf::coat_pdf(const Vec3f& wo_local, const Vec3f& wi_local) const {
  const Vec3f wo = to_coat(wo_local), wi = to_coat(wi_local);
  if (wo.z() <= 0 || wi.z() <= 0) return 0;
  if (coat_ggx_) return ggx::reflection_pdf(wo, wi, coat_alpha_);
  const Vec3f h = (wo + wi).normalized();
  return ggx::g1(wo.z(), kCoatMaskingAlpha) * gtr1::d(h.z(), coat_alpha_) / (4 * wo.z());
}

Bsdf::LobeOdds Bsdf::lobe_odds(const Vec3f& wo) const {
  const float cos_o = wo.z();
  LobeOdds odds;
  if (!glossy_) return odds;
  if (!principled_) {
    odds.specular = std::clamp(schlick(f0_, cos_o).maxCoeff(), 0.05f, 0.95f);
    return odds;
  }
  // The coat's Fresnel at its own normal (none where ωo is below it).
  const float cos_coat = coat_ > 0 ? to_coat(wo).z() : 0.0f;
  const float w_s = specular_weight_ * fresnel(cos_o).mean();
  const float w_c = cos_coat > 0 ? coat_ * fresnel_dielectric(cos_coat, kCoatEta) : 0.0f;
  const float w_d = diffuse_.mean() > kWeightCutoff ? diffuse_.mean() : 0.0f, w_v = sheen_.mean();
  float w_r = 0, w_t = 0;
  if (glass_ > 0) {
    const float F = fresnel_dielectric(cos_o, glass_eta_);
    w_r = glass_ * F;
    w_t = glass_tint_.mean() * glass_ * std::max(1e-4f, 1 - F);
  }
  const float sum = w_s + w_c + w_d + w_v + w_r + w_t;
  if (!(sum > 0)) return odds;
  odds.specular = w_s / sum;
  odds.coat = w_c / sum;
  odds.sheen = w_v / sum;
  odds.reflect = w_r / sum;
  odds.refract = w_t / sum;
  return odds;
}

float Bsdf::bump_shadowing(const Vec3f& wi) const {
  const float denominator = wi.z() * smooth_n_.z();
  const float g = denominator != 0 ? smooth_n_.dot(wi) / denominator : 0.0f;  // Cycles's safe_divide
  if (g >= 1) return 1;
  if (g < 0) return 0;
  return -g * g * g + g * g + g;
}

Rgb Bsdf::eval(const Vec3f& wo, const Vec3f& wi) const {
  const float co = wo.z(), ci = wi.z();
  if (co <= 0 || ci == 0) return Rgb::Zero();
  if (ci < 0) return glass_ > 0 ? glass(wo, wi) : Rgb::Zero();
  const Rgb f_d = bump_ ? Rgb(diffuse(wo, wi) * bump_shadowing(wi)) : diffuse(wo, wi);
  if (!glossy_) return f_d;
  Rgb f = f_d;
  if (specular_weight_ > 0) {
    const Vec3f h = (wo + wi).normalized();
    const float D = ggx::d(h.z(), alpha_), G = ggx::g1(co, alpha_) * ggx::g1(ci, alpha_);
    f += fresnel(std::max(0.0f, wi.dot(h))) * (specular_weight_ * D * G / (4 * co * ci));
  }
  if (coat_ > 0) f += coat(wo, wi);
  if (sheen_.maxCoeff() > 0) f += sheen_ * velvet::f(wo, wi, sheen_sigma_);
  if (glass_ > 0) f += glass(wo, wi);
  return f;
}

float Bsdf::pdf(const Vec3f& wo, const Vec3f& wi) const {
  if (!glossy_) return wo.z() <= 0 || wi.z() <= 0 ? 0 : wi.z() / kPiF;
  return mixture_pdf(lobe_odds(wo), wo, wi);
}

// Σ_lobes odds · density; the diffuse lobe takes the odds the others leave.
float Bsdf::mixture_pdf(const LobeOdds& odds, const Vec3f& wo, const Vec3f& wi) const {
  if (wo.z() <= 0 || wi.z() == 0) return 0;
  if (wi.z() < 0) {
    float pdf = 0;
    if (odds.refract > 0) ggx::cycles_refraction(wo, wi, glass_alpha_, glass_eta_, &pdf);
    return odds.refract * pdf;
  }
  const float p_cos = wi.z() / kPiF;
  if (!glossy_) return p_cos;
  const float p_coat = odds.coat > 0 ? odds.coat * coat_pdf(wo, wi) : 0.0f;
  const float p_reflect = odds.reflect > 0 ? odds.reflect * ggx::reflection_pdf(wo, wi, glass_alpha_) : 0.0f;
  const float p_diffuse = (1 - odds.others()) * p_cos;
  return odds.specular * ggx::reflection_pdf(wo, wi, alpha_) + p_coat + odds.sheen / (2 * kPiF) + p_reflect + p_diffuse;
}

bool Bsdf::sample(const Vec3f& wo, float u_lobe, float u1, float u2, BsdfSample* out) const {
  if (wo.z() <= 0) return false;
  Vec3f wi;
  const LobeOdds odds = lobe_odds(wo);
  const float to_sheen = odds.specular + odds.coat, to_glass = to_sheen + odds.sheen;
  if (u_lobe < odds.specular) {
    const Vec3f h = ggx::sample_visible_normal(wo, alpha_, u1, u2);
    wi = 2 * wo.dot(h) * h - wo;
  } else if (u_lobe < to_sheen) {  // the coat, about its own normal (odds.coat > 0: ωo above it)
    const Vec3f wo_c = to_coat(wo);
    const Vec3f h = ggx::sample_visible_normal(wo_c, coat_alpha_, u1, u2);
    const Vec3f wi_c = 2 * wo_c.dot(h) * h - wo_c;
    wi = coat_tilted_ ? coat_frame_.to_world(wi_c) : wi_c;
  } else if (u_lobe < to_glass) {
    wi = uniform_hemisphere_local(u1, u2);
  } else if (u_lobe < to_glass + odds.reflect + odds.refract) {
    const Vec3f h = ggx::sample_visible_normal(wo, glass_alpha_, u1, u2);
    if (u_lobe < to_glass + odds.reflect) {
      wi = 2 * wo.dot(h) * h - wo;
    } else {
      if (!ggx::refract(wo, h, glass_eta_, &wi) || wi.z() >= 0) return false;
      out->wi = wi;
      out->pdf = mixture_pdf(odds, wo, wi);
      if (!(out->pdf > 0)) return false;
      out->weight = eval(wo, wi) * (-wi.z() / out->pdf);
      return true;
    }
  } else {
    wi = cosine_sample_local(u1, u2);
  }
  if (wi.z() <= 0) return false;
  out->wi = wi.normalized();
  out->pdf = mixture_pdf(odds, wo, out->wi);
  if (!(out->pdf > 0)) return false;
  out->weight = eval(wo, out->wi) * (out->wi.z() / out->pdf);
  return true;
}

}  // namespace insitu
