// Counter-based random numbers (DESIGN.md "Randomness"): each number is a function of
// (seed, pixel, sample, dimension) alone — hashes, and the scrambled Sobol points of Sampler — so
// an image is bit-identical for any number of threads and any split of its samples into ranges.
#pragma once
#include <cstdint>

namespace insitu {

// 64-bit finalizer of MurmurHash3 / SplitMix64 (Steele et al. 2014): a bijection with full
// avalanche, applied to a combination of the four counters.
inline std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

inline std::uint64_t hash4(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample, std::uint64_t dim) {
  std::uint64_t h = mix64(seed + 0x9E3779B97F4A7C15ull);
  h = mix64(h ^ (pixel + 0x9E3779B97F4A7C15ull * 2));
  h = mix64(h ^ (sample + 0x9E3779B97F4A7C15ull * 3));
  return mix64(h ^ (dim + 0x9E3779B97F4A7C15ull * 4));
}

// A uniform float in [0, 1): the top 24 bits of the hash.
inline float hash_to_unit(std::uint64_t h) { return float(h >> 40) * (1.0f / 16777216.0f); }

// A pseudo-random permutation of [0, n) keyed by `key`: Kensler 2013, "Correlated Multi-Jittered
// Sampling", §3 (a hash that is a bijection on the smallest power-of-two domain holding n — xor
// with constants, multiplication by odd constants, xor-shifts of the masked value — walked until
// it lands below n, then rotated by the key). O(1) per index, no storage.
std::uint32_t permute(std::uint32_t i, std::uint32_t n, std::uint32_t key);

// The bits of x reversed: bit i moves to bit 31 − i (the radical inverse in base 2, times 2³²).
constexpr std::uint32_t reverse_bits(std::uint32_t x) {
  x = ((x & 0xAAAAAAAAu) >> 1) | ((x & 0x55555555u) << 1);
  x = ((x & 0xCCCCCCCCu) >> 2) | ((x & 0x33333333u) << 2);
  x = ((x & 0xF0F0F0F0u) >> 4) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x & 0xFF00FF00u) >> 8) | ((x & 0x00FF00FFu) << 8);
  return (x >> 16) | (x << 16);
}

// Laine & Karras's permutation (2011) with the constants of Vegdahl (2021), as in pbrt-v4's
// FastOwenScrambler: adding the seed and xoring in even multiples change each bit by a function of
// the bits below it only.
inline std::uint32_t laine_karras(std::uint32_t x, std::uint32_t seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

// Owen scrambling (nested uniform scrambling, Owen 1995) of a binary fraction v · 2⁻³², by a hash:
// laine_karras on the reversed bits, so that each digit of v is flipped or not by a function of the
// seed and the digits above it — the definition of an Owen scramble, which keeps every
// (t, m, s)-net a net and makes each point uniform.
inline std::uint32_t owen_scramble(std::uint32_t v, std::uint32_t seed) {
  return reverse_bits(laine_karras(reverse_bits(v), seed));
}

// Point `index` of the Sobol sequence's first two dimensions (Sobol 1967), as a 32-bit fraction:
// dimension 0 is van der Corput's (the index's bits reversed); dimension 1 has the Pascal matrix
// mod 2 as generator, direction numbers v_0 = 2³¹, v_k = v_{k−1} ⊕ (v_{k−1} >> 1). Together they
// are a (0, 2)-sequence in base 2: every aligned block of 2^m points is a (0, m, 2)-net, one point
// in each of the 2^m cells of every shape 2^−a × 2^−(m−a).
std::uint32_t sobol_2d(std::uint32_t index, int dim);

// reverse_bits(sobol_2d(index, 1)), from four tables of 256 (one per byte of the index).
std::uint32_t sobol1_reversed(std::uint32_t index);

// The hashes that scramble pair k of a pixel's numbers: the index's, and each coordinate's digits.
struct PairSeeds {
  std::uint32_t index, digits[2];
};
inline std::uint64_t sampler_base(std::uint64_t seed, std::uint64_t pixel) {
  return hash4(seed, pixel, 0, 0x534F424F4Cull);  // "SOBOL"
}
inline PairSeeds pair_seeds(std::uint64_t base, std::uint32_t pair) {
  const std::uint64_t h = mix64(base ^ (std::uint64_t(pair) * 0x9E3779B97F4A7C15ull));
  return {std::uint32_t(mix64(h)), {std::uint32_t(h), std::uint32_t(h >> 32)}};
}

// Owen-scrambled Sobol points, padded in pairs (Burley 2020, "Practical Hash-based Owen
// Scrambling", JCGT 9(4); pbrt-v4's PaddedSobolSampler): numbers 2k and 2k + 1 of a sample are the
// two coordinates of point `sample` of the 2D sequence, its order shuffled (the index itself
// Owen-scrambled) and its digits scrambled, per (seed, pixel, k):
//   u_c = owen_scramble(sobol_2d(owen_scramble(sample, s_index), c), s_c) · 2⁻³²  (top 24 bits).
// Every power-of-two prefix of a pixel's samples is then a (0, m, 2)-net in each pair — the camera
// position, a light sample, a BSDF direction — so the error falls faster than 1/√n where the
// integrand is smooth, while each number stays uniform on [0, 1) (unbiased) and pairs stay
// independent of each other. Counter-based: a function of (seed, pixel, sample,
// dimension) alone, so an image is bit-identical for any number of threads and any split of its
// samples. next() computes the formula above in the reversed domain, where sobol_2d(·, 0) is the
// identity and owen_scramble's reversals cancel: three reversals a pair instead of eight (the
// formula itself is kept in the tests and compared).
class Sampler {
 public:
  Sampler(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample)
      : base_(sampler_base(seed, pixel)), sample_reversed_(reverse_bits(std::uint32_t(sample))) {}
  float next() {
    const std::uint32_t d = dim_++, c = d & 1u;
    if (c == 0) {
      seeds_ = pair_seeds(base_, d >> 1);
      index_ = reverse_bits(laine_karras(sample_reversed_, seeds_.index));
    }
    const std::uint32_t reversed = c == 0 ? index_ : sobol1_reversed(index_);
    return float(reverse_bits(laine_karras(reversed, seeds_.digits[c])) >> 8) * (1.0f / 16777216.0f);
  }

 private:
  std::uint64_t base_;
  std::uint32_t sample_reversed_;
  std::uint32_t dim_ = 0;
  std::uint32_t index_ = 0;  // this pair's shuffled index
  PairSeeds seeds_{};
};

}  // namespace insitu
