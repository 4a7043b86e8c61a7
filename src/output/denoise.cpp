#include "output/denoise.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <stdexcept>

#include "output/denoise_edges.h"
#include "output/denoise_fit.h"
#include "output/denoise_inputs.h"
#include "output/denoise_weights.h"

namespace insitu {
namespace {

using namespace denoise_detail;

void check_sizes(const Image& photo, const Image& comp, const Image& variance, const RenderLayers& l) {
  const bool same = photo.width == comp.width && photo.height == comp.height && variance.width == comp.width &&
                    variance.height == comp.height && l.alpha.width == comp.width && l.alpha.height == comp.height;
  if (!same) throw std::logic_error("denoise: the photo, the composite and the layers differ in size");
}

int block_size(const DenoiseSettings& s, const Image& comp) {
  return s.block > 0 ? s.block : auto_block_size(comp.width, comp.height);
}

// A pixel of a whole image fitted pixel by pixel (block size 1): (1 − α) P + β₀.
void write_pixel(const Inputs& px, const Fit<kPlainFit>& fit, const Image& photo, int x, int y, Denoised& out) {
  const Rgb t = predict(fit, px.f(x, y), px.f(x, y));
  out.composite.set_rgb(x, y, ((1 - px.f(x, y)[7]) * photo.rgb(x, y) + t).max(0.0f));
  *out.variance.at(x, y) = float(fit.variance);
}

// The estimated pixels of block (bx, by): (1 − α) P + the change, from the block's fit at each
// pixel's own features and position, or, where the block's fit does not serve them
// (denoise_edges.h), from each pixel's own fit over a window of pixels (the slow form of its
// weights: such blocks are few). Returns how many pixels were fitted alone.
std::size_t write_block(const Inputs& px, const Inputs& fitted, const Fit<kPositionFit>& fit, const Image& photo,
                        const DenoiseSettings& s, int b, int bx, int by, Denoised& out) {
  const bool edge = fitted_pixel_by_pixel(px, fitted, fit, b, bx, by);
  std::size_t alone = 0;
  for (int y = by * b; y < std::min(px.height, (by + 1) * b); ++y)
    for (int x = bx * b; x < std::min(px.width, (bx + 1) * b); ++x) {
      if (!px.estimated[px.index(x, y)]) continue;
      if (edge) {
        write_pixel(px, fit_window<kPlainFit>(px, s, window_of(px, s, x, y), x, y), photo, x, y, out);
        ++alone;
        continue;
      }
      const Rgb t = predict(fit, px.f(x, y), fitted.f(bx, by));
      out.composite.set_rgb(x, y, ((1 - px.f(x, y)[7]) * photo.rgb(x, y) + t).max(0.0f));
      *out.variance.at(x, y) = float(fit.variance);
    }
  return alone;
}

}  // namespace

Denoised denoise_composite(const Image& photo, const Image& comp, const Image& variance, const RenderLayers& l,
                           const DenoiseSettings& s) {
  check_sizes(photo, comp, variance, l);
  const int b = block_size(s, comp);
  const Inputs px = gather(photo, comp, variance, l, b);
  const Inputs blocks = b > 1 ? blocks_of(px, b) : Inputs{};
  const Inputs& fitted = b > 1 ? blocks : px;
  Denoised out{comp, b, 0, Image(comp.width, comp.height, 1, 0.0f), Image(comp.width, comp.height, 1, 0.0f)};
  for (std::size_t i = 0; i < px.estimated.size(); ++i) out.estimated.data[i] = px.estimated[i];
  // Strips of kStripRows rows (of blocks): the patch distances of a strip come from the box sums
  // of the rows around it, one above and one below (so 1.25 × the terms), and its weights take
  // 8 · 8 · width · (2R + 1)² bytes (7 MB for 640 wide, R = 6).
  constexpr int kStripRows = 8;
  std::atomic<std::size_t> alone{0};
  tbb::parallel_for(0, (fitted.height + kStripRows - 1) / kStripRows, [&](int strip) {
    const int y0 = strip * kStripRows, y1 = std::min(fitted.height, y0 + kStripRows);
    const StripWeights weights = strip_weights(fitted, s, y0, y1);
    std::size_t strip_alone = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < fitted.width; ++x) {
        if (!fitted.estimated[fitted.index(x, y)]) continue;
        const Window w = window_from(fitted, s, weights, x, y);
        if (b == 1)
          write_pixel(px, fit_window<kPlainFit>(px, s, w, x, y), photo, x, y, out);
        else
          strip_alone += write_block(px, fitted, fit_window<kPositionFit>(fitted, s, w, x, y), photo, s, b, x, y, out);
      }
    alone += strip_alone;
  });
  out.pixels_fitted_alone = alone;
  return out;
}

// The same fits by reference_fit: the block's, at the pixel's own features and position; where
// that does not serve, and at block size 1, the pixel's own; then (1 − α) P + the change.
Rgb denoise_pixel_reference(const Image& photo, const Image& comp, const Image& variance, const RenderLayers& l,
                            const DenoiseSettings& s, int x, int y) {
  check_sizes(photo, comp, variance, l);
  const int b = block_size(s, comp);
  const Inputs px = gather(photo, comp, variance, l, b);
  if (!px.estimated[px.index(x, y)]) return comp.rgb(x, y);
  Rgb t = Rgb::Zero();
  const Inputs fitted = b > 1 ? blocks_of(px, b) : Inputs{};
  const int bx = x / b, by = y / b;
  const Fit<kPositionFit> block = b > 1 ? reference_fit<kPositionFit>(fitted, s, bx, by) : Fit<kPositionFit>{};
  if (b > 1 && !fitted_pixel_by_pixel(px, fitted, block, b, bx, by))
    t = predict(block, px.f(x, y), fitted.f(bx, by));
  else
    t = predict(reference_fit<kPlainFit>(px, s, x, y), px.f(x, y), px.f(x, y));
  return (t + (1 - *l.alpha.at(x, y)) * photo.rgb(x, y)).max(0.0f);
}

}  // namespace insitu
