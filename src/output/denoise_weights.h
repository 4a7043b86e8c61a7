// The denoiser's non-local-means weights (output/denoise.h) over a window of (2R + 1)² pixels j
// around pixel i: w_ij = exp(−max(0, d²_ij)), with the patch distance of Rousselle, Knaus and
// Zwicker 2012 ("Adaptive rendering with non-local means filtering") over 3 × 3 patches,
//   d²_ij = mean_p [(Y_i+p − Y_j+p)² − (v_i+p + min(v_i+p, v_j+p))] / (ε + k² (v_i+p + v_j+p)),
// the mean over the offsets p at which both i + p and j + p lie in the image. Y is the guide, v
// the variance of its mean (denoise_inputs.h). The slow form computes it pair by pair; the fast
// one, a strip of rows at a time, from box sums of each offset's terms.
#pragma once
#include <array>
#include <vector>

#include "output/denoise.h"
#include "output/denoise_inputs.h"

namespace insitu::denoise_detail {

// The window of pixel (x, y), cut by the image: its pixels, their weights row by row, and each
// feature's scale (1 / its range over the window; 0 for a feature that does not vary there,
// relative to its size, which the fit then leaves out).
struct Window {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // inclusive
  std::vector<double> weight;
  std::array<double, kFeatures> scale{};
  double total = 0;
};

// The slow, obviously correct form: every weight from its own patch distance.
Window window_of(const Inputs& in, const DenoiseSettings& s, int x, int y);

// The weights of every pixel of the rows [y0, y1) to each tap of its window, tap
// (dy + R)(2R + 1) + dx + R, 0 where the tap leaves the image.
struct StripWeights {
  int y0 = 0, taps = 0;
  std::vector<double> weight;  // (row − y0, x, tap)
  const double* at(int width, int x, int y) const { return &weight[(std::size_t(y - y0) * width + x) * taps]; }
};
StripWeights strip_weights(const Inputs& in, const DenoiseSettings& s, int y0, int y1);

// The window with its weights from the strip's (the fast form).
Window window_from(const Inputs& in, const DenoiseSettings& s, const StripWeights& strip, int x, int y);

}  // namespace insitu::denoise_detail
