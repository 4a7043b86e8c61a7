#include "output/denoise_weights.h"

#include <algorithm>
#include <cmath>

namespace insitu::denoise_detail {
namespace {

// ε of the patch distance, relative to the pixels' squared luminance: neighbours whose values
// are exact (v = 0) count as alike within about 1 %.
constexpr double kRelativeEpsilon = 1e-4;

// One pair's term: pixel a of i's patch against pixel b of j's, their difference less the
// variance the difference of two noisy means has.
double pair_term(const Inputs& in, std::size_t a, std::size_t b, double k2) {
  const double ya = in.luminance[a], yb = in.luminance[b], va = in.variance[a], vb = in.variance[b];
  const double eps = kRelativeEpsilon * 0.5 * (ya * ya + yb * yb) + 1e-30;
  return ((ya - yb) * (ya - yb) - (va + std::min(va, vb))) / (eps + k2 * (va + vb));
}

bool inside(const Inputs& in, int x, int y) { return x >= 0 && y >= 0 && x < in.width && y < in.height; }

double nl_means_weight(double d2) { return std::exp(-std::max(0.0, d2)); }

double patch_distance(const Inputs& in, int xi, int yi, int xj, int yj, double k2) {
  double sum = 0;
  int n = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if (!inside(in, xi + dx, yi + dy) || !inside(in, xj + dx, yj + dy)) continue;
      sum += pair_term(in, in.index(xi + dx, yi + dy), in.index(xj + dx, yj + dy), k2);
      ++n;
    }
  return sum / n;
}

Window window_bounds(const Inputs& in, const DenoiseSettings& s, int x, int y) {
  Window w;
  w.x0 = std::max(0, x - s.radius), w.x1 = std::min(in.width - 1, x + s.radius);
  w.y0 = std::max(0, y - s.radius), w.y1 = std::min(in.height - 1, y + s.radius);
  w.weight.reserve(std::size_t(w.x1 - w.x0 + 1) * std::size_t(w.y1 - w.y0 + 1));
  return w;
}

void scale_features(const Inputs& in, Window& w, int x, int y) {
  const float* fi = in.f(x, y);
  std::array<double, kFeatures> range{};
  for (int yy = w.y0; yy <= w.y1; ++yy)
    for (int xx = w.x0; xx <= w.x1; ++xx) {
      const float* fj = in.f(xx, yy);
      for (int d = 0; d < kFeatures; ++d) range[d] = std::max(range[d], double(std::abs(fj[d] - fi[d])));
    }
  for (int d = 0; d < kFeatures; ++d) w.scale[d] = range[d] > 1e-6 * (std::abs(fi[d]) + 1e-3) ? 1.0 / range[d] : 0.0;
}

// The horizontal 3-sums over rows [r0, r1) of one offset's terms term(a, a + o), and how many of
// the three were valid (a and a + o both in the image). Each term is computed once.
void box_sum_rows(const Inputs& in, int dx, int dy, int r0, int r1, double k2, std::vector<double>& sum,
                  std::vector<int>& count) {
  const int w = in.width;
  std::vector<double> term(std::size_t(w) + 2, 0.0);  // term[x + 1]; 0 where invalid
  std::vector<int> valid(std::size_t(w) + 2, 0);
  for (int r = r0; r < r1; ++r) {
    for (int x = 0; x < w; ++x) {
      const bool ok = inside(in, x + dx, r + dy);
      valid[std::size_t(x) + 1] = ok;
      term[std::size_t(x) + 1] = ok ? pair_term(in, in.index(x, r), in.index(x + dx, r + dy), k2) : 0.0;
    }
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(r - r0) * w + x, c = std::size_t(x) + 1;
      sum[i] = term[c - 1] + term[c] + term[c + 1];
      count[i] = valid[c - 1] + valid[c] + valid[c + 1];
    }
  }
}

}  // namespace

Window window_of(const Inputs& in, const DenoiseSettings& s, int x, int y) {
  Window w = window_bounds(in, s, x, y);
  for (int yy = w.y0; yy <= w.y1; ++yy)
    for (int xx = w.x0; xx <= w.x1; ++xx) {
      const double wt = nl_means_weight(patch_distance(in, x, y, xx, yy, s.k * s.k));
      w.weight.push_back(wt), w.total += wt;
    }
  scale_features(in, w, x, y);
  return w;
}

// One offset o = (dx, dy) at a time: the pairs' terms of the rows around the strip, their
// horizontal 3-sums, then each pixel's 3 × 3 sum d²(i, i + o) from three rows of them (the
// box-filter form of NL-means, Darbon et al. 2008). Each term is computed once, where the pixel
// by pixel form computes it once for each of the 9 patches that hold it.
StripWeights strip_weights(const Inputs& in, const DenoiseSettings& s, int y0, int y1) {
  const int R = s.radius, side = 2 * R + 1, w = in.width;
  StripWeights out{y0, side * side, std::vector<double>(std::size_t(y1 - y0) * w * side * side, 0.0)};
  const int r0 = std::max(0, y0 - 1), r1 = std::min(in.height, y1 + 1);
  std::vector<double> sum(std::size_t(r1 - r0) * w);
  std::vector<int> count(sum.size());
  for (int dy = -R; dy <= R; ++dy)
    for (int dx = -R; dx <= R; ++dx) {
      box_sum_rows(in, dx, dy, r0, r1, s.k * s.k, sum, count);
      const int tap = (dy + R) * side + dx + R;
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; ++x) {
          if (!inside(in, x + dx, y + dy)) continue;
          double d = 0;
          int n = 0;
          for (int py = std::max(r0, y - 1); py <= std::min(r1 - 1, y + 1); ++py)
            d += sum[std::size_t(py - r0) * w + x], n += count[std::size_t(py - r0) * w + x];
          out.weight[(std::size_t(y - y0) * w + x) * out.taps + tap] = nl_means_weight(d / n);
        }
    }
  return out;
}

Window window_from(const Inputs& in, const DenoiseSettings& s, const StripWeights& strip, int x, int y) {
  Window w = window_bounds(in, s, x, y);
  const double* taps = strip.at(in.width, x, y);
  const int side = 2 * s.radius + 1;
  for (int yy = w.y0; yy <= w.y1; ++yy)
    for (int xx = w.x0; xx <= w.x1; ++xx) {
      const double wt = taps[(yy - y + s.radius) * side + xx - x + s.radius];
      w.weight.push_back(wt), w.total += wt;
    }
  scale_features(in, w, x, y);
  return w;
}

}  // namespace insitu::denoise_detail
