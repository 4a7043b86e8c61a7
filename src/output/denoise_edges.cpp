#include "output/denoise_edges.h"

#include <algorithm>
#include <cmath>

namespace insitu::denoise_detail {
namespace {

constexpr double kEdgeShare = 0.25;
constexpr int kGeometry[] = {3, 4, 5, 6, 7};  // normal XYZ, depth, coverage

bool geometry_edge(const Inputs& px, const Inputs& blocks, const Fit<kPositionFit>& fit, int s, int bx, int by) {
  const float* fc = blocks.f(bx, by);
  for (int y = by * s; y < std::min(px.height, (by + 1) * s); ++y)
    for (int x = bx * s; x < std::min(px.width, (bx + 1) * s); ++x)
      for (int d : kGeometry)
        if (std::abs(double(px.f(x, y)[d]) - fc[d]) * fit.scale[std::size_t(d)] > kEdgeShare) return true;
  return false;
}

// χ²'s 99.9th percentile for k degrees of freedom: k (1 − c + z √c)³ with c = 2 / (9k).
double chi2_999(int dof) {
  const double k = dof, c = 2.0 / (9.0 * k);
  return k * std::pow(1 - c + 3.09 * std::sqrt(c), 3);
}

bool light_edge(const Inputs& px, const Inputs& blocks, int s, int bx, int by) {
  const double mean = blocks.luminance[blocks.index(bx, by)];
  double chi2 = 0;
  int n = 0;
  for (int y = by * s; y < std::min(px.height, (by + 1) * s); ++y)
    for (int x = bx * s; x < std::min(px.width, (bx + 1) * s); ++x) {
      const std::size_t i = px.index(x, y);
      if (!(px.variance[i] > 0)) continue;
      chi2 += std::pow(px.luminance[i] - mean, 2) / px.variance[i];
      ++n;
    }
  return n > 1 && chi2 > chi2_999(n - 1);
}

}  // namespace

bool fitted_pixel_by_pixel(const Inputs& px, const Inputs& blocks, const Fit<kPositionFit>& fit, int s, int bx,
                           int by) {
  return fit.effective_taps < kPositionFit || geometry_edge(px, blocks, fit, s, bx, by) ||
         light_edge(px, blocks, s, bx, by);
}

}  // namespace insitu::denoise_detail
