// What the denoiser (output/denoise.h) works on: per pixel, the render's change to the photo, the
// guide of its NL-means weights with the guide's variance, and the noise-free features; and the
// same over blocks of s × s pixels, where the fit of a large image is made.
#pragma once
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "render/render.h"

namespace insitu::denoise_detail {

// albedo RGB, normal XYZ, depth, coverage, photo luminance behind the objects (the shading
// features, kShadingFeatures); then the position x, y of the pixel's centre in blocks (a pixel of
// block 0 of 3 × 3 lies at 1/6, 1/2 or 5/6), which only the fit over blocks uses.
constexpr int kShadingFeatures = 9, kFeatures = kShadingFeatures + 2;

struct Inputs {
  int width = 0, height = 0;
  Image change;  // RGB: the composite less the photo behind the objects, C − (1 − α) P
  // Per pixel: the guide (the change's luminance divided by the albedo's) and the variance of its
  // mean; the features.
  std::vector<float> luminance, variance, features;
  // The denoiser estimates it: the render changed it (composite.h's touched_mask), or it lies
  // within 2 pixels of one the render changed (gather). Every other pixel is exact.
  std::vector<std::uint8_t> estimated;
  const float* f(int x, int y) const { return &features[(std::size_t(y) * width + x) * kFeatures]; }
  std::size_t index(int x, int y) const { return std::size_t(y) * width + x; }
};

// The pixels' inputs, for blocks of s × s. `variance` is composite_variance()'s (1 channel).
Inputs gather(const Image& photo_linear, const Image& composite_linear, const Image& variance,
              const RenderLayers& layers, int s);

// Blocks of s × s pixels (those at the right and bottom edges cut by the image): the means of the
// change, the guide and the features, the variance of the guide's mean Σ v / n², and estimated
// where any of the block's pixels is.
Inputs blocks_of(const Inputs& pixels, int s);

// The block size for an image: its short side over 480, rounded, within 1…4. The window and
// the colour tolerance were chosen on the demo at 640 × 480, where it is 1; at 1920 × 1440 it is
// 3, and a window of blocks covers the same share of the image and of the objects.
int auto_block_size(int width, int height);

}  // namespace insitu::denoise_detail
