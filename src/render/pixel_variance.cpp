#include "render/pixel_variance.h"

#include <algorithm>

namespace insitu {

SampleVariance sample_variance(const PixelSums& p) {
  if (p.batches >= kMinBatches) {
    // s_B² / B: the block sums' variance, per sample.
    const int b = p.batches;
    const double s2_block = std::max(0.0, double(p.m_batch) / double(b - 1));
    return {s2_block / kBatchSamples, b - 1};
  }
  const int n = p.samples;
  if (n < 2) return {0.0, 0};
  return {std::max(0.0, double(p.m_yy) / double(n - 1)), n - 1};
}

double variance_of_mean(const PixelSums& p) { return p.samples > 1 ? sample_variance(p).per_sample / p.samples : 0.0; }

}  // namespace insitu
