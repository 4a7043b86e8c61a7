// The GGX (Trowbridge–Reitz) microfacet distribution, isotropic, in the local frame (normal +z):
// its density, Smith's masking, and the sampling of its visible normals. One home for both
// surface models of render/bsdf.h. Tested against each other in tests/bsdf_test.cpp.
//
//   D(h)  = α² / (π ((α² − 1) cos² θ_h + 1)²)                       (Walter et al. 2007, eq. 33)
//   G1(v) = 2 / (1 + √(1 + α² tan² θ_v))                             (eq. 34)
//   D_v(h) = G1(v) max(0, v·h) D(h) / cos θ_v                         (Heitz 2014, visible normals)
// A reflected direction ωi = 2 (ωo·h) h − ωo drawn from D_ωo(h) has density
//   pdf(ωi) = D_ωo(h) / (4 |ωo·h|) = G1(ωo) D(h) / (4 cos θ_o).
#pragma once
#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace insitu::ggx {

inline float d(float cos_h, float alpha) {
  if (cos_h <= 0) return 0;
  const float a2 = alpha * alpha, c2 = cos_h * cos_h;
  const float k = c2 * (a2 - 1) + 1;
  return a2 / (kPiF * k * k);
}

inline float g1(float cos_v, float alpha) {
  if (cos_v <= 0) return 0;
  const float c2 = cos_v * cos_v, tan2 = std::max(0.0f, 1 - c2) / c2;
  return 2.0f / (1.0f + std::sqrt(1.0f + alpha * alpha * tan2));
}

// Density of reflect(wo, h) over solid angle when h is drawn from the visible normals of wo.
inline float reflection_pdf(const Vec3f& wo, const Vec3f& wi, float alpha) {
  if (wo.z() <= 0 || wi.z() <= 0) return 0;
  const Vec3f h = (wo + wi).normalized();
  return g1(wo.z(), alpha) * d(h.z(), alpha) / (4 * wo.z());
}

// Refraction (Walter et al. 2007, §5.3), for ωo on the +z side and ωi below it, η the relative index
// of the side ωi is on over ωo's. Its half vector, eq. 16, turned to +z:
//   h = ± (ωo + η ωi) / |ωo + η ωi|,
// a refraction through h where ωo·h > 0 > ωi·h. Drawn from the visible normals of ωo, ωi has
// density (eq. 17)
//   pdf(ωi) = D_ωo(h) η² |ωi·h| / (ωo·h + η ωi·h)²,
// and Cycles's refraction lobe (its Fresnel is outside, in the closure's weight) is, times |cos θi|,
//   f |cos θi| = G1(ωo) G1(ωi) D(h) η² |ωo·h| |ωi·h| / (cos θo (ωo·h + η ωi·h)²).
inline bool refraction_half(const Vec3f& wo, const Vec3f& wi, float eta, Vec3f* h) {
  if (wo.z() <= 0 || wi.z() >= 0) return false;
  Vec3f ht = wo + eta * wi;
  if (!(ht.squaredNorm() > 0)) return false;
  ht.normalize();
  if (ht.z() < 0) ht = -ht;
  *h = ht;
  return wo.dot(ht) > 0 && wi.dot(ht) < 0;
}

// The density of refract(ωo, h) for h drawn from the visible normals of ωo: 0 where no microfacet
// refracts ωo into ωi.
inline float refraction_pdf(const Vec3f& wo, const Vec3f& wi, float alpha, float eta) {
  Vec3f h;
  if (!refraction_half(wo, wi, eta, &h)) return 0;
  const float oh = wo.dot(h), ih = wi.dot(h), denominator = oh + eta * ih;
  return g1(wo.z(), alpha) * oh * d(h.z(), alpha) / wo.z() * eta * eta * -ih / (denominator * denominator);
}

// f |cos θi| and the density as Cycles 3.4 evaluates them (bsdf_microfacet_ggx_eval_transmit):
// the formulas above with |ωo·h| and |ωi·h|, for every ωi below the surface, including those no
// microfacet refracts ωo into (where ωo·h and ωi·h have the same sign). Its sampler never draws
// those; its light samples find them, which adds light to rough glass at grazing angles (up to
// 6 % of the lobe at α = 0.09, 28 % at α = 0.25, seen at 80°). insitu's eval and pdf are these,
// so that its estimator is Cycles's (docs/materials.md, "Rough glass").
inline float cycles_refraction(const Vec3f& wo, const Vec3f& wi, float alpha, float eta, float* pdf) {
  *pdf = 0;
  if (wo.z() <= 0 || wi.z() >= 0) return 0;
  const Vec3f ht = wo + eta * wi;
  const float ht2 = ht.squaredNorm();
  if (!(ht2 > 0)) return 0;
  const Vec3f h = ht / std::sqrt(ht2);
  const float oh = std::abs(wo.dot(h)), ih = std::abs(wi.dot(h)), D = d(std::abs(h.z()), alpha);
  const float common = D * eta * eta / (wo.z() * ht2);
  *pdf = g1(wo.z(), alpha) * oh * ih * common;
  return g1(wo.z(), alpha) * g1(-wi.z(), alpha) * oh * ih * common;
}

// Snell's law through the microfacet h (ωo·h > 0): ωt = −ωo/η + (c/η − √(1 − (1 − c²)/η²)) h,
// c = ωo·h; false under total internal reflection.
inline bool refract(const Vec3f& wo, const Vec3f& h, float eta, Vec3f* wt) {
  const float c = wo.dot(h), k = 1 - (1 - c * c) / (eta * eta);
  if (c <= 0 || k <= 0) return false;
  *wt = (-wo / eta + (c / eta - std::sqrt(k)) * h).normalized();
  return true;
}

// A visible normal of wo (wo.z > 0) by Heitz 2018, "Sampling the GGX distribution of visible
// normals", listing 1: stretch wo to the hemisphere configuration, sample the projected disk
// (warped to the visible half), unstretch.
inline Vec3f sample_visible_normal(const Vec3f& wo, float alpha, float u1, float u2) {
  const Vec3f vh = Vec3f(alpha * wo.x(), alpha * wo.y(), wo.z()).normalized();
  const float len2 = vh.x() * vh.x() + vh.y() * vh.y();
  const Vec3f t1 = len2 > 0 ? Vec3f(-vh.y(), vh.x(), 0) / std::sqrt(len2) : Vec3f(1, 0, 0);
  const Vec3f t2 = vh.cross(t1);
  const float r = std::sqrt(u1), phi = 2 * kPiF * u2;
  const float p1 = r * std::cos(phi), s = 0.5f * (1 + vh.z());
  const float p2 = (1 - s) * std::sqrt(std::max(0.0f, 1 - p1 * p1)) + s * r * std::sin(phi);
  const Vec3f nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1 - p1 * p1 - p2 * p2)) * vh;
  return Vec3f(alpha * nh.x(), alpha * nh.y(), std::max(1e-7f, nh.z())).normalized();
}

}  // namespace insitu::ggx
