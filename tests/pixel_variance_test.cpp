// A pixel's variance by batch means (render/pixel_variance.h): the batches are the aligned blocks
// of 16 samples whatever the range and however it was pushed; the estimate is the textbook one;
// unbiased for independent samples; and with the renderer's scrambled Sobol points it errs high,
// never low, and much less than the per-sample estimate.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/sampler.h"
#include "render/pixel_blocks.h"
#include "render/pixel_variance.h"

namespace insitu {
namespace {

// A sample of luminance y (a float: the sums are of 32-bit colours), as what the render adds.
PixelSums sample_of(double y) {
  PixelSums p;
  p.objects = Rgb::Constant(float(y)), p.samples = 1;
  return p;
}

// y of sample s: anything that shows a wrong grouping.
double y_of(int s) { return double(float(std::sin(0.37 * s) + 0.01 * s)); }

TEST(PixelVariance, BatchesAreTheAlignedBlocksOf16) {
  for (int first : {0, 5, 16, 31})
    for (int end : {first + 15, first + 40, 200, 333}) {
      PixelBlocks blocks;
      for (int s = first; s < end; ++s) push_block(blocks, first, sample_of(y_of(s)));
      const PixelSums p = fold_blocks(blocks);
      std::vector<double> Y;
      for (int k = (first + 15) / 16; 16 * (k + 1) <= end; ++k) {
        double block = 0;
        for (int s = 16 * k; s < 16 * (k + 1); ++s) block += y_of(s);
        Y.push_back(block);
      }
      double sum = 0, m2 = 0;
      for (double b : Y) sum += b;
      for (double b : Y) m2 += (b - sum / double(Y.size())) * (b - sum / double(Y.size()));
      EXPECT_EQ(p.batches, int(Y.size())) << first << " " << end;
      EXPECT_NEAR(p.batch_y, sum, 1e-5 * (1 + std::abs(sum)));
      EXPECT_NEAR(p.m_batch, m2, 1e-5 * (1 + m2));
      EXPECT_TRUE(canonical_blocks(blocks, first));
    }
}

// s_B² / B with b − 1 degrees of freedom from 8 batches on; the per-sample s² below.
TEST(PixelVariance, TheEstimateIsBatchMeansFromEightBatches) {
  for (int n : {127, 128, 256}) {
    PixelBlocks blocks;
    for (int s = 0; s < n; ++s) push_block(blocks, 0, sample_of(y_of(s)));
    const SampleVariance v = sample_variance(fold_blocks(blocks));
    double mean = 0, m2 = 0;
    const int b = n / 16;
    // A block keeps its moments to kMomentBits (render/pixel_blocks.h): half an ulp of that, 2^-17
    // relative, at each of the log2(n) + 1 levels of the tree, and the float64 reference's 1e-6.
    const auto tolerance = [&](double expected) {
      return 1e-6 + std::ldexp(1.0, -kMomentBits - 1) * (std::log2(double(n)) + 1) * std::abs(expected);
    };
    if (b >= 8) {
      std::vector<double> Y(std::size_t(b), 0.0);
      for (int s = 0; s < 16 * b; ++s) Y[std::size_t(s / 16)] += y_of(s);
      for (double y : Y) mean += y / b;
      for (double y : Y) m2 += (y - mean) * (y - mean);
      EXPECT_NEAR(v.per_sample, m2 / (b - 1) / 16, tolerance(m2 / (b - 1) / 16)) << n;
      EXPECT_EQ(v.dof, b - 1);
    } else {
      for (int s = 0; s < n; ++s) mean += y_of(s) / n;
      for (int s = 0; s < n; ++s) m2 += (y_of(s) - mean) * (y_of(s) - mean);
      EXPECT_NEAR(v.per_sample, m2 / (n - 1), tolerance(m2 / (n - 1))) << n;
      EXPECT_EQ(v.dof, n - 1);
    }
  }
}

// The centred moments against a two-pass reference in long double, at an extreme: samples of
// 10⁴ ± 10 (relative spread 10⁻³), where the raw moments Σy² − (Σy)²/n in 32 bits lose the
// variance to cancellation (checked: the test can fail), and a noise-free pixel, whose moment is
// 0 exactly.
TEST(PixelVariance, CentredMomentsHoldWhereRawOnesCancel) {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(1e4, 10.0);
  const int n = 256;
  std::vector<double> y(n);
  PixelBlocks blocks, flat;
  float raw_sum = 0, raw_sum2 = 0;
  for (int s = 0; s < n; ++s) {
    y[std::size_t(s)] = double(float(normal(rng)));
    push_block(blocks, 0, sample_of(y[std::size_t(s)]));
    push_block(flat, 0, sample_of(1e4 + 0.25));
    raw_sum += float(y[std::size_t(s)]), raw_sum2 += float(y[std::size_t(s)] * y[std::size_t(s)]);
  }
  long double mean = 0, m2 = 0;
  for (double v : y) mean += v / n;
  for (double v : y) m2 += (v - mean) * (v - mean);
  const PixelSums p = fold_blocks(blocks);
  // The means come from 32-bit sums, each off by about ulp(10⁴) ≈ 10⁻³; the differences δ of the
  // means merged are ≥ 10 √(2/128) ≈ 1.25, so each update errs by about 2 · 10⁻³ / 1.25 of itself.
  EXPECT_NEAR(double(p.m_yy) / double(m2), 1.0, 5e-3);
  EXPECT_GT(std::abs((raw_sum2 - raw_sum * raw_sum / n) / double(m2) - 1.0), 0.1) << "the raw form did not cancel";
  EXPECT_EQ(fold_blocks(flat).m_yy, 0.0f);
  EXPECT_EQ(fold_blocks(flat).m_batch, 0.0f);
}

// Independent samples of variance 4: the batch estimate's mean over 4000 pixels is 4, within 4
// standard errors of a mean of χ²_15/15 variables (relative √(2/15) each).
TEST(PixelVariance, UnbiasedForIndependentSamples) {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(10.0, 2.0);
  const int pixels = 4000;
  double total = 0;
  for (int i = 0; i < pixels; ++i) {
    PixelBlocks blocks;
    for (int s = 0; s < 256; ++s) push_block(blocks, 0, sample_of(normal(rng)));
    total += sample_variance(fold_blocks(blocks)).per_sample;
  }
  EXPECT_NEAR(total / pixels / 4.0, 1.0, 4 * std::sqrt(2.0 / 15 / pixels));
}

// A pixel's scrambled Sobol samples of a shadow edge (a disc's indicator over the pixel's square,
// the first pair of numbers) and of a smooth term: across 3000 pixels (independent scrambles) the
// true variance of the 256-sample mean against each estimate's mean. The batch estimate errs high
// (ratio ≤ 1 within the spread) and by at least twice less than the per-sample one.
TEST(PixelVariance, BatchMeansErrHighAndLessWithSobolPoints) {
  const int pixels = 3000, n = 256;
  double sum = 0, sum2 = 0, batch = 0, per_sample = 0;
  for (int i = 0; i < pixels; ++i) {
    PixelSums p;
    PixelBlocks blocks;
    for (int s = 0; s < n; ++s) {
      Sampler sampler(1, std::uint64_t(i), std::uint64_t(s));
      const double u = sampler.next(), v = sampler.next(), w = sampler.next(), z = sampler.next();
      const double y = ((u - 0.3) * (u - 0.3) + (v - 0.4) * (v - 0.4) < 0.2 ? 1.0 : 0.2) + 0.5 * w * z;
      push_block(blocks, 0, sample_of(y));
    }
    p = fold_blocks(blocks);
    const double mean = sum_y(p) / n;
    sum += mean, sum2 += mean * mean;
    batch += sample_variance(p).per_sample / n;
    per_sample += double(p.m_yy) / (n - 1) / n;
  }
  const double m = sum / pixels, truth = (sum2 / pixels - m * m) * pixels / (pixels - 1);
  const double batch_ratio = truth / (batch / pixels), sample_ratio = truth / (per_sample / pixels);
  std::printf("true variance / batch estimate %.3f, / per-sample estimate %.3f\n", batch_ratio, sample_ratio);
  EXPECT_LT(batch_ratio, 1 + 4 * std::sqrt(2.0 / pixels));
  EXPECT_GT(batch_ratio, 2 * sample_ratio);
}

}  // namespace
}  // namespace insitu
