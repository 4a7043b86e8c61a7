// The render loop's state between passes: every pixel's sums and the passes done. What a
// checkpoint and a part of a split render hold (render/checkpoint.h): an interrupted render
// resumes from it, and parts merge, to the image one uninterrupted render gives, bit for bit,
// because every sample's random numbers depend only on (seed, pixel, sample) and each pixel sums
// its samples over a tree of sample indices that no pass, thread or split changes
// (render/pixel_blocks.h).
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/math.h"

namespace insitu {

// What a pixel gathered over some of its samples. render/checkpoint.cpp writes every field but
// samples, batches and batch_y, which the pixel's samples and a block's other fields give. A
// block keeps its albedo, depth and moments rounded (render/pixel_blocks.h, round_block).
//
// The luminances a pixel's variance is of are not summed apart: the sum of y (the luminance the
// render adds, O + W − N), of w and of n (the catcher's with and without the objects) are the
// luminances of the RGB sums (sum_y, sum_w, sum_n below). Their second moments are kept centred,
// Σ(y − ȳ)² and the like, merged by Chan, Golub and LeVeque's pairwise update (1979, "Updating
// formulae and a pairwise algorithm for computing sample variances", render/pixel_blocks.cpp).
// Raw moments Σy² − (Σy)²/n cancel catastrophically on a pixel whose samples barely differ,
// which is why they needed 64 bits; centred ones lose nothing to cancellation and fit in 32, and
// a noise-free pixel's are 0 exactly.
struct PixelSums {
  Rgb objects = Rgb::Zero(), with = Rgb::Zero(), without = Rgb::Zero(), albedo = Rgb::Zero();
  Vec3f normal = Vec3f::Zero();
  float coverage = 0, depth = 0;
  // Centred moments: Σ(y − ȳ)², Σ(w − w̄)², Σ(n − n̄)², Σ(w − w̄)(n − n̄) over the samples, and
  // Σ(Y_k − Ȳ)² over the batch sums Y_k of y (render/pixel_variance.h).
  float m_yy = 0, m_ww = 0, m_nn = 0, m_wn = 0, m_batch = 0;
  // How many samples met a surface (normal, albedo, depth are over those) and saw the catcher.
  int met = 0, catcher = 0;
  int samples = 0;  // taken (a non-finite one counts, as zero): a cancelled pass leaves pixels unequal
  // The pixel's whole batches of kBatchSamples samples (render/pixel_variance.h) and the sum of
  // y over them: in a block, sum_y itself once it holds a batch, else 0 (so it is not stored).
  int batches = 0;
  double batch_y = 0;
};

// Σ of a pixel's luminances, from its RGB sums (luminance is linear): 64-bit arithmetic on the
// 32-bit sums.
inline double luminance_sum(const Rgb& c) {
  return 0.2126 * double(c[0]) + 0.7152 * double(c[1]) + 0.0722 * double(c[2]);
}
inline double sum_y(const PixelSums& p) {
  return luminance_sum(p.objects) + luminance_sum(p.with) - luminance_sum(p.without);
}
inline double sum_w(const PixelSums& p) { return luminance_sum(p.with); }
inline double sum_n(const PixelSums& p) { return luminance_sum(p.without); }

// A pixel's sums over the samples [first, first + n) it has, as the canonical aligned blocks of
// that range, in order (render/pixel_blocks.h).
using PixelBlocks = std::vector<PixelSums>;

// The render of the samples [sample_begin, sample_end) of a plan of spp per pixel (all of them
// unless the render is a part of a split one).
struct RenderState {
  int width = 0, height = 0, spp = 0;  // the plan (a part of a split render checks it is the same)
  int sample_begin = 0, sample_end = 0;
  int passes_done = 0;  // of render_passes(sample_end − sample_begin)
  int tiles_done = 0;   // of pass passes_done, in tile order (a cancelled pass)
  int spp_done = 0;     // samples every pixel still sampled has
  std::size_t nonfinite = 0;
  std::vector<PixelBlocks> pixels;
  // Adaptive sampling (render/adaptive.h): the relative standard error a pixel stops at (0: off),
  // and the pixels stopped (1), judged at the end of each pass; empty when off.
  double noise_target = 0;
  std::vector<std::uint8_t> stopped;
  // False once a stop left tiles unfinished (RenderSettings::stop_at_once): the tiles done are then
  // not [0, tiles_done), so neither a resume nor a checkpoint may use the state.
  bool resumable = true;
};

// Whether the render changed the pixel: an object covers part of it, or the catcher's estimates
// with and without the objects differ (their sums differ).
inline bool changed_pixel(const PixelSums& p) { return p.coverage != 0 || (p.with != p.without).any(); }

// |mean(O + W − N)| + mean(N): the scale a pixel's relative noise is of (render.h's noise figure,
// adaptive.h's stopping rule).
inline double pixel_value(const PixelSums& p) {
  if (p.samples == 0) return 0;
  return (std::abs(luminance(Rgb(p.objects + p.with - p.without))) + luminance(p.without)) / double(p.samples);
}

// Tiles of kTilePixels² pixels, numbered row by row; a pass renders them in that order, however
// many threads share it, so that a pass cancelled midway has done tiles [0, tiles_done).
constexpr int kTilePixels = 16;
// ⌈pixels / kTilePixels⌉ for pixels ≥ 0, without forming pixels + 15 (a checkpoint's header may
// claim a width near 2³¹).
inline int tiles_across(int pixels) { return pixels / kTilePixels + (pixels % kTilePixels != 0 ? 1 : 0); }

// The passes a render of n samples per pixel makes (progress and interruption come between them).
inline int render_passes(int n) { return n < 8 ? n : 8; }
// The first sample of pass `pass` of the samples [begin, end) (pass = passes: end).
inline int pass_start(int begin, int end, int pass) {
  return begin + int(long(end - begin) * pass / render_passes(end - begin));
}

// An adaptive render of n samples (render/adaptive.h) judges its pixels between passes, so its
// passes are short: a first of max(16, n/16) samples, the fewest a pixel takes (what an unchanged
// pixel costs), then passes of max(16, n/64), each a multiple of 16 so that every judgement sees
// whole batches (render/pixel_variance.h). 1024 spp: 64, then 16 at a time (61 passes).
inline int round_up_16(int n) { return (n + 15) / 16 * 16; }
inline int adaptive_first_pass(int n) { return std::min(n, round_up_16(std::max(16, n / 16))); }
inline int adaptive_pass(int n) { return round_up_16(std::max(16, n / 64)); }
inline int adaptive_passes(int n) {
  const int first = adaptive_first_pass(n);
  return 1 + (n - first + adaptive_pass(n) - 1) / adaptive_pass(n);
}
inline int adaptive_pass_start(int n, int pass) {
  return pass == 0 ? 0 : int(std::min<long>(n, adaptive_first_pass(n) + long(pass - 1) * adaptive_pass(n)));
}

// The passes of the state's plan, and where pass `pass` starts: adaptive with a noise target.
inline int plan_passes(const RenderState& st) {
  const int n = st.sample_end - st.sample_begin;
  return st.noise_target > 0 ? adaptive_passes(n) : render_passes(n);
}
inline int plan_pass_start(const RenderState& st, int pass) {
  const int n = st.sample_end - st.sample_begin;
  return st.noise_target > 0 ? st.sample_begin + adaptive_pass_start(n, pass)
                             : pass_start(st.sample_begin, st.sample_end, pass);
}

}  // namespace insitu
