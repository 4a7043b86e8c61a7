// The GTR1 (Berry) microfacet distribution of Cycles 3.4's clear coat, isotropic, in the local
// frame (normal +z). Burley 2012, "Physically-Based Shading at Disney", §B.2:
//   D(h) = (α² − 1) / (π ln(α²) (1 + (α² − 1) cos² θ_h)),   D = 1/π at α = 1,
// normalized so that ∫ D(h) cos θ_h dω_h = 1. Cycles evaluates the coat with this D but samples
// it with GGX's visible normals (bsdf_microfacet.h); render/bsdf.h does as Cycles does.
#pragma once
#include <cmath>

#include "core/math.h"

namespace insitu::gtr1 {

inline float d(float cos_h, float alpha) {
  if (cos_h <= 0) return 0;
  const float a2 = alpha * alpha;
  if (a2 >= 1) return 1 / kPiF;
  return (a2 - 1) / (kPiF * std::log(a2) * (1 + (a2 - 1) * cos_h * cos_h));
}

}  // namespace insitu::gtr1
