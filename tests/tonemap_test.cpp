#include <gtest/gtest.h>

#include <opencv2/photo.hpp>

#include <cmath>

#include "core/colour.h"
#include "light/equirect.h"
#include "test_util.h"
#include "output/tonemap.h"
#include "scene/pipeline.h"
#include "scene_fixture.h"

namespace insitu {
namespace {

const ToneMap kOps[] = {ToneMap::kAdaptiveLog, ToneMap::kReinhard, ToneMap::kLinear};

ToneMapSettings with(ToneMap op) { return ToneMapSettings{op, std::nullopt, 0.85}; }

TEST(ToneMapping, AllBlackFrameIsBlack) {
  const Image black(16, 8, 3, 0.0f);
  for (ToneMap op : kOps) {
    const Image out = tonemap(black, with(op));
    for (float v : out.data) ASSERT_EQ(v, 0.0f) << tonemap_name(op);
  }
}

// One pixel of 10⁶ in a grey frame: finite everywhere, the bright pixel white, the others
// neither NaN nor pushed out of [0, 1].
TEST(ToneMapping, SinglePixelOfAMillion) {
  Image img(32, 32, 3, 0.2f);
  img.set_rgb(5, 7, Rgb::Constant(1e6f));
  for (ToneMap op : kOps) {
    const Image out = tonemap(img, with(op));
    for (float v : out.data) {
      ASSERT_TRUE(std::isfinite(v)) << tonemap_name(op);
      ASSERT_GE(v, 0.0f);
      ASSERT_LE(v, 1.0f);
    }
    EXPECT_GT(out.at(5, 7)[0], 0.99f) << tonemap_name(op);
  }
  // Drago keeps the grey frame visible: not crushed to black by the one bright pixel.
  EXPECT_GT(tonemap(img, with(ToneMap::kAdaptiveLog)).at(0, 0)[0], 0.05f);
}

TEST(ToneMapping, NegativeAndNanInputsCountAsZero) {
  Image img(4, 4, 3, 0.5f);
  img.at(1, 1)[0] = -3.0f;
  img.at(2, 2)[1] = std::nanf("");
  img.at(3, 3)[2] = INFINITY;
  for (ToneMap op : kOps) {
    const Image out = tonemap(img, with(op));
    for (float v : out.data) ASSERT_TRUE(std::isfinite(v) && v >= 0 && v <= 1) << tonemap_name(op);
    EXPECT_EQ(out.at(1, 1)[0], 0.0f);
  }
}

// Reinhard by hand: a uniform frame has L̄w = δ + Lw ≈ Lw, so L = key and Ld = key/(1 + key).
TEST(ToneMapping, ReinhardOfAUniformFrame) {
  const Image img(8, 8, 3, 3.0f);
  const Image out = tonemap(img, with(ToneMap::kReinhard));
  EXPECT_NEAR(srgb_to_linear(out.at(0, 0)[0]), float(0.18 / 1.18), 1e-4f);
}

// Against OpenCV's TonemapDrago on a grey image, with OpenCV's conventions reproduced around
// ours: OpenCV first maps the image to [0, 1] by its minimum and maximum, takes the log-average
// without a key (key 1), and normalizes the result by its minimum and maximum with gamma 1. Our
// Drago output already spans [0, 1] (its first factor makes Ld(L'max) = 1). Left: its luminance is
// BT.601 gray (ours Rec.709 — equal on grey images), and its log floor is 10⁻⁴ per pixel (ours
// δ = 10⁻⁶ added) — a difference only for pixels below 10⁻³, absent here but for the minimum.
TEST(ToneMapping, DragoAgreesWithOpenCvOnGreyImages) {
  INSITU_REQUIRE_SHARED();
  Image env = linearize(read_image_file(test::shared_data() + "/hdri/hall.exr"));
  env = resize(env, 64, 32, "box");
  Image grey(64, 32, 3);
  float lo = INFINITY, hi = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      const float l = std::max(1e-3f, luminance(env.rgb(x, y)));
      grey.set_rgb(x, y, Rgb::Constant(l));
      lo = std::min(lo, l);
      hi = std::max(hi, l);
    }
  Image normalized = grey;
  for (float& v : normalized.data) v = (v - lo) / (hi - lo);
  const Image ours = tonemap(normalized, {ToneMap::kAdaptiveLog, 1.0, 0.85});
  cv::Mat m(32, 64, CV_32FC3, grey.data.data()), theirs;
  cv::createTonemapDrago(1.0f, 1.0f, 0.85f)->process(m, theirs);
  double worst = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x)
      if (normalized.at(x, y)[0] > 1e-3f)
        worst = std::max(worst, double(std::abs(srgb_to_linear(ours.at(x, y)[0]) - theirs.at<cv::Vec3f>(y, x)[0])));
  std::printf("Drago vs OpenCV: largest difference %.5f\n", worst);
  EXPECT_LT(worst, 0.01);
}

// Where the photo clipped, its colour is unknown (a white window is pink in linear light through
// the response curves): that share of the pixel is shown neutral at its luminance, as a grey
// pixel of that luminance is; elsewhere (weight 0) nothing changes, bit for bit.
TEST(ToneMapping, ClippedPhotoIsShownNeutral) {
  Image img(8, 4, 3, 0.2f), weight(8, 4, 1, 0.0f);
  const Rgb pink = Rgb(3.18f, 2.33f, 2.85f) / 4;  // the demo photo's code 255 through its response curves
  img.set_rgb(1, 1, pink);
  img.set_rgb(2, 1, Rgb::Constant(luminance(pink)));
  img.set_rgb(3, 1, pink);
  *weight.at(1, 1) = 1.0f;
  *weight.at(3, 1) = 0.5f;
  for (ToneMap op : kOps) {
    const Image plain = tonemap(img, with(op)), shown = tonemap(img, with(op), &weight);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(shown.at(1, 1)[k], shown.at(2, 1)[k], 1e-6f) << tonemap_name(op);
    EXPECT_GT(plain.at(1, 1)[0] - plain.at(1, 1)[1], 0.005f) << tonemap_name(op);  // pink without the weight
    const float half_spread = shown.at(3, 1)[0] - shown.at(3, 1)[1];               // half-way: less pink, not grey
    EXPECT_GT(half_spread, 0.0f) << tonemap_name(op);
    EXPECT_LT(half_spread, plain.at(1, 1)[0] - plain.at(1, 1)[1]) << tonemap_name(op);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 8; ++x) {
        if (*weight.at(x, y) != 0.0f) continue;
        for (int k = 0; k < 3; ++k) ASSERT_EQ(shown.at(x, y)[k], plain.at(x, y)[k]) << x << "," << y;
      }
  }
}

TEST(ToneMapping, SelectedInTheSceneFile) {
  test::SceneFixture fx;
  auto j = fx.scene;
  j["output"] = {{"image", "out/t.png"}, {"tonemap", {{"op", "reinhard"}, {"key", 0.5}}}};
  const SceneSpec spec = parse_scene_file(fx.write(j));
  EXPECT_EQ(spec.output.tonemap.op, ToneMap::kReinhard);
  EXPECT_DOUBLE_EQ(*spec.output.tonemap.key, 0.5);
  const LoadedScene s = load_scene(spec);
  write_outputs(s, render_scene(s));
  EXPECT_TRUE(std::filesystem::exists(fx.dir.file("out/t.png")));
  j["output"] = {{"tonemap", "drago"}};
  EXPECT_THROW(parse_scene_file(fx.write(j)), InputError);
}

}  // namespace
}  // namespace insitu
