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
