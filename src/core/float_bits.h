// A float32 rounded to fewer significand bits, to nearest with ties to even (IEEE 754's default
// rounding, which a conversion to binary16 applies to its 10 stored bits), keeping float32's
// exponent range. The bits dropped are zero, so planes of such numbers compress well
// (render/checkpoint.h); the value is the one a narrower format would hold.
#pragma once
#include <cstdint>
#include <cstring>

namespace insitu {

// A float32's bits and back (std::bit_cast, before C++20).
inline std::uint32_t float_bits(float x) {
  std::uint32_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
inline float bits_float(std::uint32_t u) {
  float x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}

// x with `bits` (1..23) of its 23 stored significand bits kept; infinities and NaN as they are,
// and x itself where rounding up would overflow to infinity.
float round_significand(float x, int bits);

// The same from frexp and ldexp (the slow, plainly correct version the test compares with): for
// normal numbers only (a subnormal's significand has fewer bits).
float round_significand_reference(float x, int bits);

}  // namespace insitu
