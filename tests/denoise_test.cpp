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

// The columns x < 15 untouched (W = N, variance 0, as composite_variance gives them): those
// farther than 2 pixels from a touched one come back bit for bit; the two beside the touched ones
// are estimated with them.
TEST(Denoise, UntouchedPixelsStayBitForBit) {
  Floor f;
  f.fill(
      random_texture, [](int, int) { return 1.0; }, 0.05, 2);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < 15; ++x) {
      f.layers.without_objects.set_rgb(x, y, Rgb::Constant(1.0f));  // W = N: untouched
      *f.variance.at(x, y) = 0.0f;
    }
  const Denoised d = denoise_composite(f.photo, f.noisy, f.variance, f.layers);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < 13; ++x) {
      for (int c = 0; c < 3; ++c) ASSERT_EQ(d.composite.rgb(x, y)[c], f.noisy.rgb(x, y)[c]) << x << "," << y;
      ASSERT_EQ(*d.estimated.at(x, y), 0.0f);
    }
  for (int y = 0; y < kH; ++y) EXPECT_EQ(*d.estimated.at(13, y), 1.0f) << y;
  EXPECT_NE(d.composite.rgb(30, 10)[0], f.noisy.rgb(30, 10)[0]);
}

// A faint, broad shadow at 16 spp: each sample sees the occluder with probability 0.1 and then
// takes 0.4 of the floor's light, so the floor is 4 % darker on average and a pixel's change is
// −0.4 t k / 16 for its k ~ Binomial(16, 0.1) hits, of variance (0.4 t)² 0.1 · 0.9 / 16. The
// pixels with no hit (0.9¹⁶ = 19 % of them) the render left untouched: the photo's, W = N,
// variance 0. Estimated with their neighbours, they take the shadow: their error falls from its
// depth to less than half of it (to 0.26 of it; 1 without the rule, where they are exact).
TEST(Denoise, PixelsWhoseSamplesAllMissedAFaintShadowTakeIt) {
  Floor f;
  f.fill(
      random_texture, [](int, int) { return 0.96; }, 0.0, 12);
  std::mt19937 rng(13);
  std::binomial_distribution<int> hits(16, 0.1);
  std::vector<std::pair<int, int>> missed;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float t = f.photo.rgb(x, y)[0];
      const int k = hits(rng);
      f.noisy.set_rgb(x, y, Rgb::Constant(t * (1 - 0.4f * float(k) / 16)));
      *f.variance.at(x, y) = k > 0 ? float(std::pow(0.4 * t, 2) * 0.1 * 0.9 / 16) : 0.0f;
      if (k > 0) continue;
      f.layers.without_objects.set_rgb(x, y, f.layers.with_objects.rgb(x, y));
      missed.emplace_back(x, y);
    }
  const Denoised d = denoise_composite(f.photo, f.noisy, f.variance, f.layers);
  double before = 0, after = 0;
  for (const auto& [x, y] : missed) {
    before += std::pow(luminance(f.noisy.rgb(x, y)) - luminance(f.truth.rgb(x, y)), 2);
    after += std::pow(luminance(d.composite.rgb(x, y)) - luminance(f.truth.rgb(x, y)), 2);
  }
  ASSERT_GT(missed.size(), 100u);
  before = std::sqrt(before / double(missed.size())), after = std::sqrt(after / double(missed.size()));
  EXPECT_GT(before, 0.01);  // 0.04 of a texture of 0.2–0.8
  EXPECT_LT(after, 0.5 * before) << before;
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

// A flat floor of w × h pixels whose change is 0.3 under Gaussian noise of σ = 0.05 (its variance
// known exactly), every pixel touched.
struct FlatFloor {
  int w, h;
  Image photo, noisy, variance;
  RenderLayers l;
  FlatFloor(int w_, int h_, unsigned seed)
      : w(w_), h(h_), photo(w, h, 3, 0.5f), noisy(w, h, 3), variance(w, h, 1, 0.0025f) {
    l.alpha = Image(w, h, 1, 0.0f), l.with_objects = Image(w, h, 3, 1.0f), l.without_objects = Image(w, h, 3, 0.9f);
    l.albedo = Image(w, h, 3, 0.5f), l.depth = Image(w, h, 1, 3.0f), l.normal = Image(w, h, 3);
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal(0, 0.05);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        l.normal.set_rgb(x, y, Rgb(0, 1, 0));
        noisy.set_rgb(x, y, Rgb::Constant(float(0.3 + normal(rng))));
      }
  }
  // The RMS error of a denoised composite over the pixels at least `margin` from the border.
  double interior_error(const Image& out, int margin) const {
    double sum = 0;
    int n = 0;
    for (int y = margin; y < h - margin; ++y)
      for (int x = margin; x < w - margin; ++x, ++n) sum += std::pow(luminance(out.rgb(x, y)) - 0.3, 2);
    return std::sqrt(sum / n);
  }
};

// A window of blocks of s × s pixels averages s² pixels in each tap: on a flat noisy floor the
// error left falls by about s (σ/s per tap, as many taps), here 2: 0.51 measured. The position's
// two unknowns cost little away from the image's border, where a window is cut and the fit
// extrapolates to its edge (0.81 over the whole of a 40 × 32 image with R = 4, against 0.54
// without them).
TEST(Denoise, BlocksOfFourPixelsHalveTheNoiseLeft) {
  const FlatFloor f(96, 96, 7);
  DenoiseSettings pixels, blocks;
  pixels.block = 1, blocks.block = 2;
  pixels.radius = blocks.radius = 4;
  const double e1 = f.interior_error(denoise_composite(f.photo, f.noisy, f.variance, f.l, pixels).composite, 8);
  const double e2 = f.interior_error(denoise_composite(f.photo, f.noisy, f.variance, f.l, blocks).composite, 8);
  EXPECT_LT(e2, 0.7 * e1) << e1;
  EXPECT_GT(e2, 0.3 * e1) << e1;
}

// An object's silhouette that cuts blocks of 3 × 3 (x = 19.5, inside the block of columns 18–20):
// the object (α = 1, nearer, facing another way, a flat 0.7) before a textured floor whose change
// is 0.2 × its texture. The change mixes texture and coverage (0.2 t (1 − α) + 0.7 α), which no
// fit linear in the features holds across the edge: the block's fit, evaluated at each pixel of
// the cut block, left them 0.52 off (RMS; dark stair steps along a table leg at 1920 × 1440). The
// pixels of a block that holds an edge are fitted one by one, and stay within the noise (0.012).
TEST(Denoise, ASilhouetteThatCutsABlockStaysSharp) {
  Floor f;
  const double sigma = 0.02;
  f.fill(
      random_texture, [](int, int) { return 0.2; }, sigma, 8);
  std::mt19937 rng(9);
  std::normal_distribution<double> normal(0, sigma);
  for (int y = 0; y < kH; ++y)
    for (int x = 20; x < kW; ++x) {
      *f.layers.alpha.at(x, y) = 1.0f, *f.layers.depth.at(x, y) = 2.0f;
      f.layers.normal.set_rgb(x, y, Rgb(1, 0, 0));
      f.layers.albedo.set_rgb(x, y, Rgb::Constant(0.7f));
      f.truth.set_rgb(x, y, Rgb::Constant(0.7f));
      f.noisy.set_rgb(x, y, Rgb::Constant(float(0.7 + normal(rng))));
    }
  DenoiseSettings s;
  s.block = 3;
  const Denoised d = denoise_composite(f.photo, f.noisy, f.variance, f.layers, s);
  EXPECT_LT(rms(d.composite, f.truth, 18, 21), sigma);
}

// A shadow's edge that cuts blocks of 3 × 3 (x = 19.5), which no feature sees: the block's fit
// gives the cut block's pixels their mean; its guides spread beyond their noise, so they are
// fitted one by one, and the columns beside the edge keep the contrast.
TEST(Denoise, AShadowsEdgeThatCutsABlockStaysSharp) {
  Floor f;
  const double sigma = 0.03;
  f.fill(
      random_texture, [](int x, int) { return x < 20 ? 0.3 : 0.9; }, sigma, 5);
  DenoiseSettings s;
  s.block = 3;
  const Denoised d = denoise_composite(f.photo, f.noisy, f.variance, f.layers, s);
  EXPECT_LT(rms(d.composite, f.truth, 18, 21), sigma);
  EXPECT_LT(rms(d.composite, f.truth, 0, 14), 0.4 * sigma);
}

// The edge test's false alarms: on a flat floor of pure noise (its variance known exactly), the
// guides' χ² passes its 99.9th percentile in about one block in a thousand, so of 1280 blocks of
// 3 × 3 about 1.3 are fitted pixel by pixel (9 pixels each); P(more than 6 blocks) < 10⁻³ by
// Poisson. A block whose window finds no block like it, and a silhouette's blocks, are.
TEST(Denoise, NoiseAloneSendsFewBlocksToBeFittedPixelByPixel) {
  FlatFloor f(120, 96, 11);
  DenoiseSettings s;
  s.block = 3;
  const std::size_t noise = denoise_composite(f.photo, f.noisy, f.variance, f.l, s).pixels_fitted_alone;
  EXPECT_LE(noise, 6u * 9u);
  // A spot of light that fills block (20, 16) evenly, 10σ above the floor: no edge inside the
  // block, but its patch is like no other's, so its window's weights count about one tap.
  FlatFloor spot = f;
  for (int y = 48; y < 51; ++y)
    for (int x = 60; x < 63; ++x) spot.noisy.set_rgb(x, y, spot.noisy.rgb(x, y) + Rgb::Constant(0.5f));
  EXPECT_GE(denoise_composite(spot.photo, spot.noisy, spot.variance, spot.l, s).pixels_fitted_alone, noise + 9);
  for (int y = 0; y < f.h; ++y) *f.l.alpha.at(61, y) = 1.0f;  // a thin object's column cuts blocks 20
  const std::size_t alone = denoise_composite(f.photo, f.noisy, f.variance, f.l, s).pixels_fitted_alone;
  EXPECT_GE(alone, std::size_t(f.h) * 3);
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
