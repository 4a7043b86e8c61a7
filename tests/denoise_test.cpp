// The composite's denoiser (output/denoise.h): the fast smoother against the explicit solve, the
// photo's untouched pixels, exactness on images the first-order fit can represent, and the
// noise it removes and says it leaves.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/colour.h"
#include "output/denoise.h"
#include "output/denoise_inputs.h"

namespace insitu {
namespace {

constexpr int kW = 40, kH = 32;

// A floor seen from above: a photo whose texture is also the catcher's albedo (as a
// photo-derived albedo is), every pixel touched (W ≠ N), depth and normal constant.
struct Floor {
  Image photo{kW, kH, 3}, truth{kW, kH, 3}, noisy{kW, kH, 3}, variance{kW, kH, 1};
  RenderLayers layers;
  Floor() {
    layers.alpha = Image(kW, kH, 1, 0.0f);
    layers.with_objects = Image(kW, kH, 3, 1.0f);
    layers.without_objects = Image(kW, kH, 3, 0.9f);
    layers.albedo = Image(kW, kH, 3);
    layers.normal = Image(kW, kH, 3);
    layers.depth = Image(kW, kH, 1, 3.0f);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) layers.normal.set_rgb(x, y, Rgb(0, 1, 0));
  }
  // texture(x, y) in [0.2, 0.8]; the true composite shade(x, y) · texture; noise of standard error σ.
  template <class Texture, class Shade>
  void fill(Texture texture, Shade shade, double sigma, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal(0, 1);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const float t = float(texture(x, y));
        photo.set_rgb(x, y, Rgb::Constant(t));
        layers.albedo.set_rgb(x, y, Rgb::Constant(t));
        truth.set_rgb(x, y, Rgb::Constant(float(shade(x, y) * t)));
        noisy.set_rgb(x, y, (truth.rgb(x, y) + Rgb::Constant(float(sigma * normal(rng)))));
        *variance.at(x, y) = float(sigma * sigma);
      }
  }
};

double random_texture(int x, int y) { return 0.2 + 0.6 * double((x * 7919 + y * 104729) % 1000) / 999; }

// RMS of (a − b) over the pixels x in [x0, x1), luminance.
double rms(const Image& a, const Image& b, int x0 = 0, int x1 = kW) {
  double s = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = x0; x < x1; ++x) s += std::pow(luminance(a.rgb(x, y)) - luminance(b.rgb(x, y)), 2);
  return std::sqrt(s / (kH * (x1 - x0)));
}

// The fast form (box-summed patch distances by strips of rows, packed sums, LDLT) against the
// slow one (each weight from its own patch distance, a QR solve), per pixel and over blocks.
void expect_fast_is_reference(int block) {
  Floor f;
  f.fill(
      random_texture, [](int x, int) { return x < 20 ? 0.4 : 0.8; }, 0.05, 1);
  *f.layers.alpha.at(10, 10) = 0.5f, *f.layers.depth.at(10, 10) = 2.0f;  // an object's edge
  DenoiseSettings s;
  s.block = block;
  const Denoised fast = denoise_composite(f.photo, f.noisy, f.variance, f.layers, s);
  // Every pixel: the corners and edges, where windows and patches are cut by the image, and the
  // rows on both sides of the fast form's strips of 8 rows.
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const Rgb slow = denoise_pixel_reference(f.photo, f.noisy, f.variance, f.layers, s, x, y);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(fast.composite.rgb(x, y)[c], slow[c], 1e-5) << x << "," << y;
    }
}

TEST(Denoise, TheFastSmootherIsTheReferenceSolve) { expect_fast_is_reference(1); }

// Blocks of 3 × 3 do not divide 40 × 32: the last column and row of blocks are cut.
TEST(Denoise, TheFastSmootherIsTheReferenceSolveOverBlocks) {
  expect_fast_is_reference(2);
  expect_fast_is_reference(3);
}

TEST(Denoise, UntouchedPixelsStayBitForBit) {
  Floor f;
  f.fill(
      random_texture, [](int, int) { return 1.0; }, 0.05, 2);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < 15; ++x) f.layers.without_objects.set_rgb(x, y, Rgb::Constant(1.0f));  // W = N: untouched
  const Denoised d = denoise_composite(f.photo, f.noisy, f.variance, f.layers);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < 15; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(d.composite.rgb(x, y)[c], f.noisy.rgb(x, y)[c]) << x << "," << y;
  EXPECT_NE(d.composite.rgb(30, 10)[0], f.noisy.rgb(30, 10)[0]);
}

// Without noise, an image that is linear in the features is what a first-order fit reproduces:
// the output is the input, up to the ridge's pull on the slopes (1e-3 of the weight, on features
// scaled to ±1: at most 1e-3 of the texture's contrast, 0.6 · 0.5 here).
// Over blocks the same holds pixel by pixel: each pixel takes the fit at its own albedo, so the
// texture within a block is kept.
TEST(Denoise, ANoiseFreeImageLinearInTheAlbedoComesBackUnchanged) {
  Floor f;
  f.fill(
      random_texture, [](int, int) { return 0.5; }, 0.0, 3);
  for (int block : {1, 2, 3}) {
    DenoiseSettings s;
    s.block = block;
    const Denoised d = denoise_composite(f.photo, f.truth, f.variance, f.layers, s);
    EXPECT_LT(rms(d.composite, f.truth), 3e-4) << block;
  }
}

// A textured floor under noise: the texture is kept (a box filter of the window would leave the
// texture's own spread, 0.17 · 0.5 = 0.087, as error) and the noise falls.
TEST(Denoise, NoiseFallsAndTheTextureStays) {
  Floor f;
  const double sigma = 0.05;
  f.fill(
      random_texture, [](int, int) { return 0.5; }, sigma, 4);
  const Denoised d = denoise_composite(f.photo, f.noisy, f.variance, f.layers);
  EXPECT_NEAR(rms(f.noisy, f.truth), sigma, 0.1 * sigma);
  EXPECT_LT(rms(d.composite, f.truth), 0.3 * sigma);
}

// A shadow's edge, which no feature sees: the NL-means weights keep the two sides apart, so the
// columns beside the edge keep the contrast (the error there stays below the noise's).
TEST(Denoise, AShadowsEdgeStaysSharp) {
  Floor f;
  const double sigma = 0.03;
  f.fill(
      random_texture, [](int x, int) { return x < 20 ? 0.3 : 0.9; }, sigma, 5);
  const Denoised d = denoise_composite(f.photo, f.noisy, f.variance, f.layers);
  EXPECT_LT(rms(d.composite, f.truth, 18, 22), sigma);
  EXPECT_LT(rms(d.composite, f.truth, 0, 14), 0.4 * sigma);
}

// The variance the denoiser states for its output (Σ l_j² v_j) against the squared error it makes,
// over many pixels of a flat, noisy floor: within a factor of 2 either way.
TEST(Denoise, TheStatedVarianceIsTheErrorLeft) {
  Floor f;
  f.fill([](int, int) { return 0.5; }, [](int, int) { return 0.6; }, 0.05, 6);
  const Denoised d = denoise_composite(f.photo, f.noisy, f.variance, f.layers);
  double stated = 0;
  for (float v : d.variance.data) stated += v;
  stated /= double(d.variance.data.size());
  const double error2 = std::pow(rms(d.composite, f.truth), 2);
  EXPECT_GT(error2, 0.5 * stated);
  EXPECT_LT(error2, 2.0 * stated);
}

// A window of blocks of s × s pixels averages s² pixels in each tap: on a flat noisy floor the
// error left falls by about s (σ/s per tap, as many taps), here 2 (0.535 measured).
TEST(Denoise, BlocksOfFourPixelsHalveTheNoiseLeft) {
  Floor f;
  const double sigma = 0.05;
  f.fill([](int, int) { return 0.5; }, [](int, int) { return 0.6; }, sigma, 7);
  DenoiseSettings pixels, blocks;
  pixels.block = 1, blocks.block = 2;
  pixels.radius = blocks.radius = 4;
  const double e1 = rms(denoise_composite(f.photo, f.noisy, f.variance, f.layers, pixels).composite, f.truth);
  const double e2 = rms(denoise_composite(f.photo, f.noisy, f.variance, f.layers, blocks).composite, f.truth);
  EXPECT_LT(e2, 0.7 * e1);
  EXPECT_GT(e2, 0.3 * e1);
}

// The block size follows the image's short side: 1 on the demo's 640 × 480, where the window was
// chosen, 3 on a 1920 × 1440 still; never 0, and at most 4.
TEST(Denoise, TheBlockSizeFollowsTheImagesShortSide) {
  using denoise_detail::auto_block_size;
  EXPECT_EQ(auto_block_size(640, 480), 1);
  EXPECT_EQ(auto_block_size(1920, 1440), 3);
  EXPECT_EQ(auto_block_size(1920, 1080), 2);
  EXPECT_EQ(auto_block_size(1440, 1920), 3);
  EXPECT_EQ(auto_block_size(40, 32), 1);
  EXPECT_EQ(auto_block_size(8000, 6000), 4);
}

}  // namespace
}  // namespace insitu
