#include "render/bsdf.h"

#include <algorithm>

#include "render/mesh.h"

namespace insitu {

namespace {

Rgb schlick(const Rgb& f0, float cos_theta) {
  const float m = std::clamp(1.0f - cos_theta, 0.0f, 1.0f), m5 = m * m * m * m * m;
  return f0 + (Rgb::Ones() - f0) * m5;
}

// GGX normal distribution D(h) for a local half-vector with cos θ_h = h.z.
float ggx_d(float cos_h, float alpha) {
  if (cos_h <= 0) return 0;
  const float a2 = alpha * alpha, c2 = cos_h * cos_h;
  const float d = c2 * (a2 - 1) + 1;
  return a2 / (kPiF * d * d);
}

// Smith's G1 for GGX: 2 / (1 + √(1 + α² tan² θ)).
float ggx_g1(float cos_v, float alpha) {
  if (cos_v <= 0) return 0;
  const float c2 = cos_v * cos_v, tan2 = std::max(0.0f, 1 - c2) / c2;
  return 2.0f / (1.0f + std::sqrt(1.0f + alpha * alpha * tan2));
}

}  // namespace

Bsdf::Bsdf(const Rgb& diffuse, const Rgb& f0, float alpha)
    : diffuse_(diffuse),
      f0_(f0.max(0.0f).min(1.0f)),
      alpha_(std::clamp(alpha, 1e-3f, 1.0f)),
      glossy_(f0.maxCoeff() > 0) {}

Bsdf Bsdf::from_material(const Material& m, const Rgb& base_colour) {
  // Walter et al. 2007: α = √(2/(Ns + 2)).
  const float alpha = std::sqrt(2.0f / (std::max(0.0f, m.ns) + 2.0f));
  return Bsdf(base_colour, m.ks, alpha);
}

float Bsdf::specular_probability(float cos_o) const {
  return glossy_ ? std::clamp(schlick(f0_, cos_o).maxCoeff(), 0.05f, 0.95f) : 0.0f;
}

Rgb Bsdf::eval(const Vec3f& wo, const Vec3f& wi) const {
  const float co = wo.z(), ci = wi.z();
  if (co <= 0 || ci <= 0) return Rgb::Zero();
  if (!glossy_) return diffuse_ / kPiF;
  const Rgb diffuse = (Rgb::Ones() - schlick(f0_, co)) * diffuse_ / kPiF;
  const Vec3f h = (wo + wi).normalized();
  const float D = ggx_d(h.z(), alpha_), G = ggx_g1(co, alpha_) * ggx_g1(ci, alpha_);
  const Rgb F = schlick(f0_, std::max(0.0f, wi.dot(h)));
  return diffuse + F * (D * G / (4 * co * ci));
}

float Bsdf::pdf(const Vec3f& wo, const Vec3f& wi) const {
  if (wo.z() <= 0 || wi.z() <= 0) return 0;
  const float p_cos = wi.z() / kPiF;
  if (!glossy_) return p_cos;
  const Vec3f h = (wo + wi).normalized();
  const float p_spec = ggx_d(h.z(), alpha_) * h.z() / (4 * std::abs(wo.dot(h)));
  const float ps = specular_probability(wo.z());
  return ps * p_spec + (1 - ps) * p_cos;
}

bool Bsdf::sample(const Vec3f& wo, float u_lobe, float u1, float u2, BsdfSample* out) const {
  if (wo.z() <= 0) return false;
  Vec3f wi;
  if (glossy_ && u_lobe < specular_probability(wo.z())) {
    // Half-vector from D(h) cos θ_h: tan² θ_h = α² u1 / (1 − u1).
    const float tan2 = alpha_ * alpha_ * u1 / std::max(1e-7f, 1 - u1);
    const float cos_h = 1 / std::sqrt(1 + tan2), sin_h = std::sqrt(std::max(0.0f, 1 - cos_h * cos_h));
    const float phi = 2 * kPiF * u2;
    const Vec3f h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
    wi = 2 * wo.dot(h) * h - wo;
  } else {
    wi = cosine_sample_local(u1, u2);
  }
  if (wi.z() <= 0) return false;
  out->wi = wi.normalized();
  out->pdf = pdf(wo, out->wi);
  if (!(out->pdf > 0)) return false;
  out->weight = eval(wo, out->wi) * (out->wi.z() / out->pdf);
  return true;
}

}  // namespace insitu
