#include "render/adaptive.h"

#include "render/pixel_variance.h"

#include <algorithm>
#include <cmath>

namespace insitu {

// s² (n − 1) / χ²_0.05(n − 1), χ²_p(k) ≈ k (1 − 2/(9k) + z_p √(2/(9k)))³ (Wilson & Hilferty
// 1931), z_0.05 = −1.645. Below k = 3 the approximation's cube goes negative: infinite there.
double variance_upper_bound_factor(int n) {
  const double k = n - 1;
  if (k < 3) return INFINITY;
  const double a = 2 / (9 * k), c = 1 - a - 1.645 * std::sqrt(a);
  return 1 / (c * c * c);
}

double honest_relative_error(const std::vector<PixelSums>& sums, int w, int h, std::size_t i) {
  const PixelSums& p = sums[i];
  if (p.samples < 2) return INFINITY;
  const int x = int(i % std::size_t(w)), y = int(i / std::size_t(w));
  double pooled = 0;
  int count = 0, dof = 0;
  for (int ny = std::max(0, y - 1); ny <= std::min(h - 1, y + 1); ++ny)
    for (int nx = std::max(0, x - 1); nx <= std::min(w - 1, x + 1); ++nx) {
      const PixelSums& q = sums[std::size_t(ny) * std::size_t(w) + std::size_t(nx)];
      if (!changed_pixel(q) || q.samples < 2) continue;
      const SampleVariance v = sample_variance(q);
      pooled += v.per_sample, dof += v.dof, ++count;
    }
  // Each estimate raised to its bound: the pooled mean over `count` pixels with about Σ dof
  // degrees of freedom, the pixel's own with its own.
  const double pooled_bound = count > 0 && pooled > 0 ? pooled / count * variance_upper_bound_factor(dof + 1) : 0.0;
  const SampleVariance own = sample_variance(p);
  const double own_bound = own.per_sample > 0 ? own.per_sample * variance_upper_bound_factor(own.dof + 1) : 0.0;
  const double variance = std::max(own_bound, pooled_bound);
  if (variance == 0) return 0;
  const double value = pixel_value(p);
  return value > 0 ? std::sqrt(variance / p.samples) / value : INFINITY;
}

void stop_converged(const std::vector<PixelSums>& sums, int w, int h, double target,
                    std::vector<std::uint8_t>& stopped) {
  std::vector<std::uint8_t> next = stopped;
  for (std::size_t i = 0; i < sums.size(); ++i) {
    const PixelSums& p = sums[i];
    if (stopped[i] || p.samples < kMinAdaptiveSamples) continue;
    if (!changed_pixel(p) && p.catcher == 0)
      next[i] = 1;
    else if (honest_relative_error(sums, w, h, i) <= target)
      next[i] = 1;
  }
  stopped = std::move(next);
}

}  // namespace insitu
