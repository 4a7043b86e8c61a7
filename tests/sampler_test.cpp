// The counter-based random numbers (core/sampler.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "scene/pipeline.h"
#include "core/sampler.h"
#include <OpenImageIO/imageio.h>

#include "scene_fixture.h"

namespace insitu {
namespace {

// permute() is a bijection of [0, n) for every n and key (a slow, obvious check: every index is
// hit once), and keys give different orders.
TEST(Sampler, PermuteIsABijection) {
  for (std::uint32_t n : {1u, 2u, 3u, 7u, 16u, 100u, 144u, 1000u, 4097u})
    for (std::uint32_t key : {0u, 1u, 0xdeadbeefu, 12345u}) {
      std::vector<int> hits(n, 0);
      for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t j = permute(i, n, key);
        ASSERT_LT(j, n);
        ++hits[j];
      }
      for (std::uint32_t j = 0; j < n; ++j) ASSERT_EQ(hits[j], 1) << "n " << n << " key " << key;
    }
  int same = 0;
  for (std::uint32_t i = 0; i < 144; ++i) same += permute(i, 144, 1) == permute(i, 144, 2);
  EXPECT_LT(same, 20);
}

// sobol_2d against its definition, computed the slow way: dimension 0 puts index bit j at fraction
// bit j (bit 31 − j of the word); dimension 1 multiplies by the Pascal matrix mod 2, whose entry
// (j, k) is C(k, j) mod 2 — odd exactly when the bits of j are a subset of k's (Lucas's theorem).
std::uint32_t sobol_by_matrix(std::uint32_t index, int dim) {
  std::uint32_t v = 0;
  for (int j = 0; j < 32; ++j) {
    int bit = 0;
    for (int k = 0; k < 32; ++k) {
      const bool entry = dim == 0 ? j == k : (j & k) == j;
      bit ^= entry && ((index >> k) & 1u);
    }
    v |= std::uint32_t(bit) << (31 - j);
  }
  return v;
}

TEST(Sampler, SobolMatchesItsGeneratorMatrices) {
  std::uint64_t h = 1;
  for (std::uint32_t i = 0; i < 5000; ++i) {
    h = mix64(h + i);
    for (const std::uint32_t index : {i, std::uint32_t(h), ~i})
      for (int dim : {0, 1}) ASSERT_EQ(sobol_2d(index, dim), sobol_by_matrix(index, dim)) << index << " dim " << dim;
    ASSERT_EQ(sobol1_reversed(std::uint32_t(h)), reverse_bits(sobol_2d(std::uint32_t(h), 1)));
  }
}

// Sampler::next() computes, in the reversed domain, the formula of its comment; here the formula
// itself, over pixels, samples and 12 dimensions.
TEST(Sampler, NextIsTheScrambledSobolFormula) {
  for (const std::uint64_t seed : {1ull, 987654321ull})
    for (const std::uint64_t pixel : {0ull, 77ull, 1ull << 40})
      for (std::uint64_t sample = 0; sample < 300; sample += 7) {
        Sampler sampler(seed, pixel, sample);
        const std::uint64_t base = sampler_base(seed, pixel);
        for (std::uint32_t d = 0; d < 12; ++d) {
          const PairSeeds ps = pair_seeds(base, d / 2);
          const std::uint32_t index = owen_scramble(std::uint32_t(sample), ps.index);
          const std::uint32_t v = owen_scramble(sobol_2d(index, int(d % 2)), ps.digits[d % 2]);
          ASSERT_EQ(sampler.next(), float(v >> 8) / 16777216.0f) << "sample " << sample << " dim " << d;
        }
      }
}

// The definition of an Owen scramble: flipping a digit of the input flips the same digit of the
// output and leaves every digit above it as it was; and the map is a bijection.
TEST(Sampler, OwenScrambleFlipsEachDigitByTheDigitsAboveIt) {
  std::uint64_t h = 7;
  for (int trial = 0; trial < 2000; ++trial) {
    h = mix64(h + std::uint64_t(trial));
    const std::uint32_t v = std::uint32_t(h), seed = std::uint32_t(h >> 32);
    const std::uint32_t out = owen_scramble(v, seed);
    for (int digit = 0; digit < 32; ++digit) {  // digit 0: the fraction's first bit (the word's top)
      const std::uint32_t bit = 0x80000000u >> digit;
      const std::uint32_t flipped = owen_scramble(v ^ bit, seed);
      const std::uint32_t above = ~(0xFFFFFFFFu >> digit);
      ASSERT_EQ(flipped & above, out & above) << "digit " << digit;
      ASSERT_EQ(flipped & bit, (out & bit) ^ bit) << "digit " << digit;
    }
  }
  std::vector<bool> hit(1 << 16, false);
  for (std::uint32_t v = 0; v < (1u << 16); ++v) hit[owen_scramble(v << 16, 0xC0FFEEu) >> 16] = true;
  EXPECT_TRUE(std::all_of(hit.begin(), hit.end(), [](bool b) { return b; }));
}

// Every power-of-two prefix of a pixel's samples is a (0, m, 2)-net in each pair of dimensions:
// one point in each of the 2^m cells of every shape 2^−a × 2^−(m−a).
TEST(Sampler, EveryPowerOfTwoPrefixIsANetInEachPair) {
  for (const std::uint64_t pixel : {0ull, 12345ull})
    for (int m = 0; m <= 10; ++m) {
      const int n = 1 << m;
      std::vector<std::array<std::uint32_t, 8>> points(static_cast<std::size_t>(n));
      for (int s = 0; s < n; ++s) {
        Sampler sampler(3, pixel, std::uint64_t(s));
        for (auto& u : points[std::size_t(s)]) u = std::uint32_t(sampler.next() * 16777216.0f);
      }
      for (int pair = 0; pair < 4; ++pair)
        for (int a = 0; a <= m; ++a) {
          std::vector<int> cells(std::size_t(n), 0);
          for (const auto& p : points) {
            const std::uint32_t cx = p[std::size_t(2 * pair)] >> (24 - a),
                                cy = p[std::size_t(2 * pair + 1)] >> (24 - (m - a));
            ++cells[(cx << (m - a)) | cy];
          }
          for (int c : cells) ASSERT_EQ(c, 1) << "pixel " << pixel << " m " << m << " pair " << pair << " a " << a;
        }
    }
}

// What the nets buy, and that nothing is lost: the mean of f(u, v) = u v (∫ = 1/4) over 256 samples
// of a pixel. Independent uniform samples err by σ/√n, σ² = 1/9 − 1/16; scrambled nets, over 256
// pixels, by less than a quarter of that; the mean over pixels is unbiased within 4 standard
// errors. Dimensions 0 and 4 of the same samples (pairs 0 and 2) are uncorrelated (|r| < 4/√n).
TEST(Sampler, ScrambledNetsBeatIndependentSamplesWithoutBias) {
  const int n = 256, pixels = 256;
  const double sigma_mc = std::sqrt(1.0 / 9 - 1.0 / 16) / std::sqrt(double(n));
  double sum_sq = 0, sum = 0;
  for (int px = 0; px < pixels; ++px) {
    double mean = 0, sx = 0, sy = 0, sxy = 0, sxx = 0, syy = 0;
    for (int s = 0; s < n; ++s) {
      Sampler sampler(11, std::uint64_t(px), std::uint64_t(s));
      const double u = sampler.next(), v = sampler.next();
      sampler.next(), sampler.next();
      const double w = sampler.next();
      mean += u * v / n;
      sx += u, sy += w, sxy += u * w, sxx += u * u, syy += w * w;
    }
    const double r = (sxy - sx * sy / n) / std::sqrt((sxx - sx * sx / n) * (syy - sy * sy / n));
    ASSERT_LT(std::abs(r), 4 / std::sqrt(double(n))) << "pixel " << px;
    sum_sq += (mean - 0.25) * (mean - 0.25);
    sum += mean - 0.25;
  }
  EXPECT_LT(std::sqrt(sum_sq / pixels), 0.25 * sigma_mc);
  EXPECT_LT(std::abs(sum / pixels), 4 * std::sqrt(sum_sq / pixels) / std::sqrt(double(pixels)));
}

}  // namespace
}  // namespace insitu
