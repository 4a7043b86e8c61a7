#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "output/composite.h"
#include "scene/pipeline.h"
#include "scene_fixture.h"

namespace insitu {
namespace {

// One pixel's layers as the render loop leaves them, from per-sample catcher luminances w, n
// (grey), `covered` of the samples on an object of radiance `object`.
RenderLayers one_pixel(const std::vector<std::pair<double, double>>& wn, int covered, float object) {
  RenderLayers l;
  for (Image* img : {&l.objects, &l.with_objects, &l.without_objects}) *img = Image(1, 1, 3);
  for (Image* img : {&l.alpha, &l.ratio_variance, &l.difference_variance, &l.catcher_samples}) *img = Image(1, 1, 1);
  const int k = int(wn.size()) + covered;
  double W = 0, N = 0, W2 = 0, N2 = 0, WN = 0;
  for (const auto& [w, n] : wn) W += w, N += n, W2 += w * w, N2 += n * n, WN += w * n;
  l.with_objects.set_rgb(0, 0, Rgb::Constant(float(W / k)));
  l.without_objects.set_rgb(0, 0, Rgb::Constant(float(N / k)));
  *l.alpha.at(0, 0) = float(covered) / float(k);
  l.objects.set_rgb(0, 0, Rgb::Constant(object * float(covered) / float(k)));
  const double R = W / N, n_mean = N / k;
  *l.ratio_variance.at(0, 0) = float((W2 - 2 * R * WN + R * R * N2) / (double(k) * (k - 1) * n_mean * n_mean));
  *l.difference_variance.at(0, 0) = float(((W2 - 2 * WN + N2) - (W - N) * (W - N) / k) / (double(k) * (k - 1)));
  *l.catcher_samples.at(0, 0) = float(wn.size());
  return l;
}

// The firefly of issue 9: a pixel 99 % covered by a table leg, one sample of 144 on the floor,
// whose no-object estimate is nearly 0 while the leg's bounce lights the with-object one: W/N = 210.
// The ratio form would make the floor 210 × (1 − α) P = 2.1 P; the guard takes the additive form.
TEST(Composite, ContactPixelWithOneCatcherSampleUsesTheAdditiveForm) {
  const RenderLayers l = one_pixel({{0.21, 0.001}}, 143, 0.1f);
  Image photo(1, 1, 3, 0.5f);
  EXPECT_FALSE(ratio_is_reliable(photo, l, 0, 0));
  const float a = *l.alpha.at(0, 0);
  const Image c = composite(photo, l, CompositeMode::kRatio);
  const float additive = 0.1f * a + (1 - a) * 0.5f + (0.21f - 0.001f) / 144;
  EXPECT_NEAR(c.at(0, 0)[0], additive, 1e-6f);
  EXPECT_LT(c.at(0, 0)[0], 0.11f);  // the ratio form gives 0.1 · 0.99 + 0.01 · 0.5 · 210 = 1.15
}

// A well-sampled shadow keeps the ratio form: an umbra (W = 0 for every sample) has a ratio of
// variance 0 and is the ratio's best case; open floor (W = N bit for bit) too.
TEST(Composite, WellSampledShadowsKeepTheRatioForm) {
  Image photo(1, 1, 3, 0.5f);
  std::vector<std::pair<double, double>> umbra, open;
  for (int i = 0; i < 64; ++i) {
    const double n = 0.2 + 0.1 * (i % 7);
    umbra.push_back({0.0, n});
    open.push_back({n, n});
  }
  EXPECT_TRUE(ratio_is_reliable(photo, one_pixel(umbra, 0, 0), 0, 0));
  EXPECT_TRUE(ratio_is_reliable(photo, one_pixel(open, 0, 0), 0, 0));
  EXPECT_EQ(composite(photo, one_pixel(open, 0, 0), CompositeMode::kRatio).at(0, 0)[0], 0.5f);
}

// A cube resting on the floor: at 16 spp against a 1024-spp reference, over the pixels where the
// guard chose the additive form, the composite's error must be no larger than the ratio form's
// (the guard picks the estimator with the smaller standard error).
TEST(Composite, ContactShadowHasNoFireflies) {
  test::SceneFixture fx;
  fx.dir.write(
      "cube.obj",
      "v 0 0 -1\nv 0.6 0 -1\nv 0.6 0 -0.4\nv 0 0 -0.4\nv 0 0.6 -1\nv 0.6 0.6 -1\nv 0.6 0.6 -0.4\nv 0 0.6 -0.4\n"
      "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n");
  write_image(fx.dir.file("photo.png"), Image(fx.width, fx.height, 3, 0.5f));  // a plain grey floor
  auto j = fx.scene;
  j["objects"] = {{{"mesh", "cube.obj"}}};
  j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  j["camera"] = {{"eye", {1.6, 0.5, 0.6}}, {"look", {0.3, 0.05, -0.7}}, {"hfov_deg", 50}};
  auto render = [&](int spp, std::uint64_t seed) {
    j["render"] = {{"integrator", "path"}, {"spp", spp}, {"seed", seed}};
    const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
    return std::make_pair(render_scene(s), s.photo_linear);
  };
  const auto [ref, photo] = render(1024, 77);
  const auto [low, photo2] = render(16, 1);
  RenderLayers unguarded = low.layers;
  unguarded.catcher_samples = Image();  // no statistics: the ratio everywhere
  const Image guarded_c = composite(photo, low.layers, CompositeMode::kRatio);
  const Image ratio_c = composite(photo, unguarded, CompositeMode::kRatio);
  const Image mask = touched_mask(ref.layers);
  // Over the pixels where the guard chose the additive form (elsewhere both are the same).
  double worst_guarded = 0, worst_ratio = 0, se_guarded = 0, se_ratio = 0;
  int changed = 0, contact = 0;
  for (int y = 0; y < photo.height; ++y)
    for (int x = 0; x < photo.width; ++x) {
      if (*mask.at(x, y) == 0) continue;
      ++changed;
      if (ratio_is_reliable(photo, low.layers, x, y)) continue;
      ++contact;
      const double r = luminance(ref.composite_linear.rgb(x, y));
      const double eg = luminance(guarded_c.rgb(x, y)) - r, er = luminance(ratio_c.rgb(x, y)) - r;
      worst_guarded = std::max(worst_guarded, std::abs(eg));
      worst_ratio = std::max(worst_ratio, std::abs(er));
      se_guarded += eg * eg, se_ratio += er * er;
    }
  ASSERT_GT(changed, 100);
  ASSERT_GT(contact, 0) << "the view should hold pixels where the ratio is unreliable";
  std::printf(
      "additive at %d of %d changed pixels; there worst error %.4f (guarded) vs %.4f (ratio), RMS %.4f vs %.4f\n",
      contact, changed, worst_guarded, worst_ratio, std::sqrt(se_guarded / contact), std::sqrt(se_ratio / contact));
  EXPECT_LE(se_guarded, se_ratio);
}

// changed_mask: the objects, and the pixels whose 3 × 3 mean change exceeds 3 % of the photo; a
// change of 1 % everywhere (a far wall that the objects barely touch) is not "changed".
TEST(Composite, ChangedMaskIsWhereTheChangeShows) {
  const int w = 20, h = 10;
  Image photo(w, h, 3, 0.5f), comp(w, h, 3, 0.505f);  // 1 % everywhere
  RenderLayers l;
  l.alpha = Image(w, h, 1, 0.0f);
  for (int y = 2; y < 7; ++y)
    for (int x = 2; x < 7; ++x) comp.set_rgb(x, y, Rgb::Constant(0.4f));  // a shadow, −20 %
  *l.alpha.at(15, 5) = 0.5f;                                              // an object's edge
  const Image m = changed_mask(photo, comp, l);
  EXPECT_EQ(*m.at(4, 4), 1.0f);
  EXPECT_EQ(*m.at(15, 5), 1.0f);
  EXPECT_EQ(*m.at(12, 1), 0.0f);
  EXPECT_EQ(*m.at(0, 9), 0.0f);
}

// The bisection over the running maximum gives the scan's value bit for bit, on a curve with dips
// and plateaus (where the scan's "made non-decreasing" matters), below its first value, beyond its
// last, exactly on its values and on NaN; and it inverts: g(code) comes back as the code.
TEST(Composite, InverseResponseByBisectionIsTheScans) {
  ResponseCurve r;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0, 1);
  for (int k = 0; k < 3; ++k)
    for (int z = 0; z < 256; ++z) {
      const float rising = std::pow(float(z) / 255.0f, 2.2f) * float(k + 1);
      r.g[std::size_t(k)][std::size_t(z)] = z % 37 == 5            ? 0.5f * rising
                                            : z % 41 == 7 && z > 0 ? r.g[std::size_t(k)][std::size_t(z - 1)]
                                                                   : rising;
    }
  const InverseResponse inverse(r);
  std::vector<float> values = {
      -1.0f, 0.0f, 1e-9f, 3.0f, 4.0f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()};
  for (int k = 0; k < 3; ++k)
    for (float g : r.g[std::size_t(k)]) values.push_back(g), values.push_back(std::nextafter(g, 10.0f));
  for (int i = 0; i < 100000; ++i) values.push_back(3.2f * u(rng));
  for (int k = 0; k < 3; ++k)
    for (float v : values) {
      const float scan = inverse_response(r, k, v), bisection = inverse(k, v);
      ASSERT_EQ(std::memcmp(&scan, &bisection, sizeof(float)), 0) << "channel " << k << " value " << v;
    }
  EXPECT_NEAR(inverse(1, r.g[1][200]), 200.0f / 255.0f, 1e-6f);
}

}  // namespace
}  // namespace insitu
