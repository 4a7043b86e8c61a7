#include "core/float_bits.h"

#include <cmath>

namespace insitu {

// With d = 23 − bits dropped bits: adding 2^(d−1) − 1, plus 1 when the last kept bit is odd,
// and clearing the d low bits rounds the significand to nearest, ties to even; a carry out of
// the significand steps the exponent up, as it should (1.111…1 rounds to 2.0).
float round_significand(float x, int bits) {
  std::uint32_t u = float_bits(x);
  if ((u & 0x7f800000u) == 0x7f800000u || bits >= 23) return x;
  const int drop = 23 - bits;
  const std::uint32_t odd = (u >> drop) & 1u;
  u = (u + (1u << (drop - 1)) - 1u + odd) & ~((1u << drop) - 1u);
  const float r = bits_float(u);
  return std::isinf(r) ? x : r;
}

// x = m·2^e with m in [0.5, 1): m·2^(bits+1) rounded to an integer (nearbyint rounds half to
// even) keeps 1 + bits significant bits.
float round_significand_reference(float x, int bits) {
  if (!std::isfinite(x) || x == 0) return x;
  int e = 0;
  const double m = std::frexp(double(x), &e);
  const double r = std::ldexp(std::nearbyint(std::ldexp(m, bits + 1)), e - bits - 1);
  return std::isinf(float(r)) ? x : float(r);
}

}  // namespace insitu
