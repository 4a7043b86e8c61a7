#include "core/sampler.h"

namespace insitu {

namespace {

// Direction numbers of the Sobol sequence's dimension 1: v_0 = 2³¹, v_k = v_{k−1} ⊕ (v_{k−1} >> 1).
struct PascalDirections {
  std::uint32_t v[32];
  constexpr PascalDirections() : v() {
    v[0] = 0x80000000u;
    for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
  }
};
constexpr PascalDirections kPascal;

// sobol1_reversed by bytes: table b holds, for each byte x, the xor of reverse_bits(v_k) over the
// bits k of x << 8b.
struct ReversedTables {
  std::uint32_t t[4][256];
  constexpr ReversedTables() : t() {
    for (int b = 0; b < 4; ++b)
      for (int x = 0; x < 256; ++x)
        for (int k = 0; k < 8; ++k)
          if ((x >> k) & 1) t[b][x] ^= reverse_bits(kPascal.v[8 * b + k]);
  }
};
constexpr ReversedTables kReversed;

}  // namespace

std::uint32_t sobol1_reversed(std::uint32_t index) {
  return kReversed.t[0][index & 0xFFu] ^ kReversed.t[1][(index >> 8) & 0xFFu] ^ kReversed.t[2][(index >> 16) & 0xFFu] ^
         kReversed.t[3][index >> 24];
}

std::uint32_t sobol_2d(std::uint32_t index, int dim) {
  if (dim == 0) return reverse_bits(index);
  std::uint32_t v = 0;
  for (; index != 0; index &= index - 1) v ^= kPascal.v[__builtin_ctz(index)];
  return v;
}

std::uint32_t permute(std::uint32_t i, std::uint32_t n, std::uint32_t key) {
  if (n <= 1) return 0;
  std::uint32_t w = n - 1;  // the mask of the power-of-two domain
  w |= w >> 1;
  w |= w >> 2;
  w |= w >> 4;
  w |= w >> 8;
  w |= w >> 16;
  do {
    i ^= key;
    i *= 0xe170893du;
    i ^= key >> 16;
    i ^= (i & w) >> 4;
    i ^= key >> 8;
    i *= 0x0929eb3fu;
    i ^= key >> 23;
    i ^= (i & w) >> 1;
    i *= 1u | key >> 27;
    i *= 0x6935fa69u;
    i ^= (i & w) >> 11;
    i *= 0x74dcb303u;
    i ^= (i & w) >> 2;
    i *= 0x9e501cc3u;
    i ^= (i & w) >> 2;
    i *= 0xc860a3dfu;
    i &= w;
    i ^= i >> 5;
  } while (i >= n);
  return (i + key) % n;
}

}  // namespace insitu
