// Counter-based random numbers (DESIGN.md "Randomness"): each number is a hash of
// (seed, pixel, sample, dimension), so an image is bit-identical for any number of threads and
// any split of its samples into ranges.
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

class Sampler {
 public:
  Sampler(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample)
      : seed_(seed), pixel_(pixel), sample_(sample) {}
  float next() { return hash_to_unit(hash4(seed_, pixel_, sample_, dim_++)); }

 private:
  std::uint64_t seed_, pixel_, sample_;
  std::uint64_t dim_ = 0;
};

}  // namespace insitu
