// The Ashikhmin velvet lobe of Cycles 3.4's Velvet BSDF (bsdf_ashikhmin_velvet.h), which
// Blender's glTF importer adds to the Principled BSDF for KHR_materials_sheen, in the local frame
// (normal +z). Ashikhmin & Premože 2007's inverted-Gaussian microfacets:
//   D(h) = exp(−cot² θ_h / σ²) / (π σ² sin⁴ θ_h),  σ = max(sheenRoughness, 0.01),
// normalized: ∫ D cos θ_h dω_h = (2/σ²) ∫₀^∞ t e^(−t²/σ²) dt = 1 (t = cot θ_h); with Cycles's
// shadowing G = min(1, 2 (n·h)/(ωo·h) cos θ_o, 2 (n·h)/(ωo·h) cos θ_i),
//   f(ωo, ωi) = D G / (4 cos θ_o cos θ_i),
// sampled uniformly over the hemisphere (pdf 1/2π), as Cycles samples it.
#pragma once
#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace insitu::velvet {

inline float sigma(float sheen_roughness) { return std::max(sheen_roughness, 0.01f); }

inline float d(float cos_h, float sigma) {
  const float sin2 = 1 - cos_h * cos_h;
  if (cos_h <= 0 || sin2 <= 0) return 0;
  const float inv_s2 = 1 / (sigma * sigma);
  return std::exp(-cos_h * cos_h / sin2 * inv_s2) * inv_s2 / (kPiF * sin2 * sin2);
}

// f for unit local directions, both above the surface; 0 where Cycles's guards return 0.
inline float f(const Vec3f& wo, const Vec3f& wi, float sigma) {
  const float co = wo.z(), ci = wi.z();
  if (!(co > 0 && ci > 0)) return 0;
  const Vec3f h = (wo + wi).normalized();
  const float cos_nh = h.z(), cos_ho = std::abs(wo.dot(h));
  if (!(std::abs(cos_nh) < 1 - 1e-5f && cos_ho > 1e-5f)) return 0;
  const float r = std::max(cos_nh / cos_ho, 1e-5f);
  const float G = std::min({1.0f, 2 * r * co, 2 * r * ci});
  return d(cos_nh, sigma) * G / (4 * co * ci);
}

}  // namespace insitu::velvet
