// What a BSDF's sampler does, measured for the tests of sampling routines (bsdf_test.cpp,
// glass_test.cpp).
#pragma once
#include <cmath>
#include <cstdint>

#include "core/sampler.h"
#include "render/bsdf.h"

namespace insitu::test {

struct Fraction {
  double p, se;
};

// The fraction of n samples from ωo that succeed, and its standard error: ∫ pdf dω over where the
// sampler goes must equal it.
inline Fraction success_fraction(const Bsdf& b, const Vec3f& wo, int n = 200000) {
  int ok = 0;
  for (int k = 0; k < n; ++k) {
    Sampler s(6, std::uint64_t(k), 2);
    BsdfSample bs;
    const float ul = s.next(), u1 = s.next(), u2 = s.next();
    ok += b.sample(wo, ul, u1, u2, &bs);
  }
  const double p = double(ok) / n;
  return {p, std::sqrt(p * (1 - p) / n)};
}

}  // namespace insitu::test
