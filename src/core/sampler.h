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
inline std::uint32_t reverse_bits(std::uint32_t x) {
  x = ((x & 0xAAAAAAAAu) >> 1) | ((x & 0x55555555u) << 1);
  x = ((x & 0xCCCCCCCCu) >> 2) | ((x & 0x33333333u) << 2);
  x = ((x & 0xF0F0F0F0u) >> 4) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x & 0xFF00FF00u) >> 8) | ((x & 0x00FF00FFu) << 8);
  return (x >> 16) | (x << 16);
}

// Owen scrambling (nested uniform scrambling, Owen 1995) of a binary fraction v · 2⁻³², by a hash:
// Laine & Karras's permutation (2011) with the constants of Vegdahl (2021), as in pbrt-v4's
// FastOwenScrambler, on the reversed bits. In the reversed word, adding the seed and xoring in an
// even multiple change each bit by a function of the bits below it only; reversed back, each
// digit of v is flipped or not by a function of the seed and the digits above it — the definition
// of an Owen scramble, which keeps every (t, m, s)-net a net and makes each point uniform.
inline std::uint32_t owen_scramble(std::uint32_t v, std::uint32_t seed) {
  v = reverse_bits(v);
  v ^= v * 0x3d20adeau;
  v += seed;
  v *= (seed >> 16) | 1u;
  v ^= v * 0x05526c56u;
  v ^= v * 0x53a22864u;
  return reverse_bits(v);
}

// Point `index` of the Sobol sequence's first two dimensions (Sobol 1967), as a 32-bit fraction:
// dimension 0 is van der Corput's (the index's bits reversed); dimension 1 has the Pascal matrix
// mod 2 as generator, direction numbers v_0 = 2³¹, v_k = v_{k−1} ⊕ (v_{k−1} >> 1). Together they
// are a (0, 2)-sequence in base 2: every aligned block of 2^m points is a (0, m, 2)-net, one point
// in each of the 2^m cells of every shape 2^−a × 2^−(m−a).
std::uint32_t sobol_2d(std::uint32_t index, int dim);

// Owen-scrambled Sobol points, padded in pairs (Burley 2020, "Practical Hash-based Owen
// Scrambling", JCGT 9(4); pbrt-v4's PaddedSobolSampler): numbers 2k and 2k + 1 of a sample are the
// two coordinates of point `sample` of the 2D sequence, its order shuffled (the index itself
// Owen-scrambled) and its digits scrambled, per (seed, pixel, k). Every power-of-two prefix of a
// pixel's samples is then a (0, m, 2)-net in each pair — the camera position, a light sample, a
// BSDF direction — so the error falls faster than 1/√n where the integrand is smooth, while each
// number stays uniform on [0, 1) (unbiased) and pairs stay independent of each other. Counter-
// based as before: a function of (seed, pixel, sample, dimension) alone, so an image is
// bit-identical for any number of threads and any split of its samples.
class Sampler {
 public:
  Sampler(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample)
      : seed_(seed), pixel_(pixel), sample_(std::uint32_t(sample)) {}
  float next() {
    const std::uint32_t d = dim_++;
    if ((d & 1u) == 0) {
      const std::uint64_t h = hash4(seed_, pixel_, d >> 1, 0x534F424F4Cull);  // "SOBOL"
      index_ = owen_scramble(sample_, std::uint32_t(h));
      digits_ = mix64(h);
    }
    const std::uint32_t seed = std::uint32_t(digits_ >> (32 * (d & 1u)));
    return float(owen_scramble(sobol_2d(index_, int(d & 1u)), seed) >> 8) * (1.0f / 16777216.0f);
  }

 private:
  std::uint64_t seed_, pixel_;
  std::uint32_t sample_;
  std::uint32_t dim_ = 0;
  std::uint32_t index_ = 0;   // this pair's shuffled index
  std::uint64_t digits_ = 0;  // this pair's two digit-scrambling seeds
};

}  // namespace insitu
