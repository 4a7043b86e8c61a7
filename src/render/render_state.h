// The render loop's state between passes: every pixel's sums and the passes done. What a
// checkpoint holds (render/checkpoint.h): an interrupted render resumes from it to the image an
// uninterrupted one gives, bit for bit, because each pixel adds its samples in index order and
// every sample's random numbers depend only on (seed, pixel, sample).
#pragma once
#include <cstddef>
#include <vector>

#include "core/math.h"

namespace insitu {

// What a pixel has gathered so far. Samples are added in index order, pass after pass, so the
// sums are the same whatever the passes and the threads. render/checkpoint.cpp writes every field.
struct PixelSums {
  Rgb objects = Rgb::Zero(), with = Rgb::Zero(), without = Rgb::Zero(), albedo = Rgb::Zero();
  Vec3f normal = Vec3f::Zero();
  double coverage = 0, depth = 0, y = 0, y2 = 0;
  // The catcher's luminance with (w) and without (n) the objects: sums of w, n, w², n², w·n over
  // all samples, and how many samples saw the catcher, for the composite's choice of estimator.
  double w = 0, n = 0, w2 = 0, n2 = 0, wn = 0;
  int met = 0, catcher = 0;
  int samples = 0;  // taken (a non-finite one counts, as zero): a cancelled pass leaves pixels unequal
};

struct RenderState {
  int width = 0, height = 0, spp = 0;  // the plan: the strata depend on spp
  int passes_done = 0;                 // of render_passes(spp)
  int tiles_done = 0;                  // of pass passes_done, in tile order (a cancelled pass)
  int spp_done = 0;                    // samples every pixel has
  std::size_t nonfinite = 0;
  std::vector<PixelSums> sums;
};

// Tiles of kTilePixels² pixels, numbered row by row; a pass renders them in that order, however
// many threads share it, so that a pass cancelled midway has done tiles [0, tiles_done).
constexpr int kTilePixels = 16;
inline int tiles_across(int pixels) { return (pixels + kTilePixels - 1) / kTilePixels; }

// The passes a render of spp samples per pixel makes (progress and interruption come between them).
inline int render_passes(int spp) { return spp < 8 ? spp : 8; }
// The first sample of pass `pass` (pass = passes: spp).
inline int pass_start(int spp, int pass) { return int(long(spp) * pass / render_passes(spp)); }

}  // namespace insitu
