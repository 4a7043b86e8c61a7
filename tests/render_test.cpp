#include <gtest/gtest.h>

#include <cmath>

#include "scene/pipeline.h"
#include "core/sampler.h"
#include "render/pixel_blocks.h"
#include <OpenImageIO/imageio.h>

#include "scene_fixture.h"

namespace insitu {
namespace {

// The camera-space z at which the ray through pixel position uv meets the floor y = 0 inside
// [box_min, box_max] (x and z), or nothing.
std::optional<double> floor_z(const Camera& cam, const Vec2d& uv, double x_lo, double x_hi, double z_lo, double z_hi) {
  const Ray r = cam.ray(uv);
  if (!(r.dir.y() < 0)) return std::nullopt;
  const Vec3d o = r.origin.cast<double>(), d = r.dir.cast<double>();
  const Vec3d p = o + (-o.y() / d.y()) * d;
  if (p.x() < x_lo || p.x() > x_hi || p.z() < z_lo || p.z() > z_hi) return std::nullopt;
  return (cam.R_cam_from_world * p + cam.t_cam_from_world).z();
}

// The face of the room box [lo, hi] that the ray through uv leaves by (2·axis + 0 for the max
// side, 1 for the min side) and the exit's camera-space z.
std::pair<int, double> wall_z(const Camera& cam, const Vec2d& uv, const Vec3d& lo, const Vec3d& hi) {
  const Ray r = cam.ray(uv);
  const Vec3d o = r.origin.cast<double>(), d = r.dir.cast<double>();
  double t_exit = 1e300;
  int face = -1;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) continue;
    const double t = ((d[k] > 0 ? hi[k] : lo[k]) - o[k]) / d[k];
    if (t < t_exit) t_exit = t, face = 2 * k + (d[k] > 0 ? 0 : 1);
  }
  return {face, (cam.R_cam_from_world * (o + t_exit * d) + cam.t_cam_from_world).z()};
}

// depth.Z is camera-space z, as Cycles and Nuke read it: in every pixel whose four corners all
// see the floor, it lies between the corners' z (z is monotonic across a pixel of a plane);
// where no corner sees anything it is the documented no-hit value. With a room box the floor ends
// at the walls, and the walls are local-scene surfaces too: every pixel sees the floor or a wall,
// never a distance of 10⁷, and a pixel whose corners all see one wall lies between their z.
TEST(Render, DepthIsCameraSpaceZAndNoHitIsDocumented) {
  test::SceneFixture fx;
  for (const bool box : {false, true}) {
    auto j = fx.scene;
    j["camera"] = {{"eye", {0.5, 1.0, 1.5}}, {"look", {0.5, 0.8, -0.5}}, {"hfov_deg", 60}};
    j["render"] = {{"integrator", "path"}, {"spp", 4}};
    j["objects"] = nlohmann::json::array();
    j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
    const double big = 1e30;
    double x_lo = -big, x_hi = big, z_lo = -big, z_hi = big;
    if (box) {
      j["environment"] = {{"image", "env.exr"},
                          {"room_box", {{"min", {-1, 0, -4}}, {"max", {2, 2.5, 2}}, {"capture", {0.5, 1, 0}}}}};
      x_lo = -1, x_hi = 2, z_lo = -4, z_hi = 2;
    }
    const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
    const RenderResult r = render_scene(s);
    int floor_pixels = 0, empty_pixels = 0, wall_pixels = 0;
    for (int y = 0; y < s.camera.height; ++y)
      for (int x = 0; x < s.camera.width; ++x) {
        std::vector<double> zs;
        for (int c = 0; c < 4; ++c)
          if (auto z = floor_z(s.camera, {x + c % 2, y + c / 2}, x_lo, x_hi, z_lo, z_hi)) zs.push_back(*z);
        const float depth = *r.layers.depth.at(x, y);
        ASSERT_TRUE(std::isfinite(depth));
        if (box && zs.empty()) {
          std::vector<double> wz;
          for (int c = 0; c < 4; ++c) {
            const auto [face, z] = wall_z(s.camera, {x + c % 2, y + c / 2}, Vec3d(-1, 0, -4), Vec3d(2, 2.5, 2));
            if (face == wall_z(s.camera, {x, y}, Vec3d(-1, 0, -4), Vec3d(2, 2.5, 2)).first) wz.push_back(z);
          }
          if (wz.size() < 4) continue;
          ++wall_pixels;
          const auto [lo, hi] = std::minmax_element(wz.begin(), wz.end());
          EXPECT_GE(depth, *lo * (1 - 1e-5)) << x << "," << y << " wall";
          EXPECT_LE(depth, *hi * (1 + 1e-5)) << x << "," << y << " wall";
        } else if (zs.size() == 4) {
          ++floor_pixels;
          const auto [lo, hi] = std::minmax_element(zs.begin(), zs.end());
          EXPECT_GE(depth, *lo * (1 - 1e-5)) << x << "," << y << " box " << box;
          EXPECT_LE(depth, *hi * (1 + 1e-5)) << x << "," << y << " box " << box;
        } else if (zs.empty()) {
          ++empty_pixels;
          EXPECT_EQ(depth, kNoHitDepth) << x << "," << y << " box " << box;
        }
      }
    EXPECT_GT(floor_pixels, 100);
    if (box)
      EXPECT_GT(wall_pixels, 20) << "the view should show the walls";
    else
      EXPECT_GT(empty_pixels, 20) << "the view should show some sky";
  }
}

// The noise figure after each pass covers the same pixels (all the render changed), so for a
// deterministic integrator, whose only noise is the pixel footprint, it falls as the samples grow:
// for independent samples σ_mean ∝ 1/√n, and stratification only makes it fall faster. Each pass
// may not exceed the one before by more than the estimate's own sampling error allows (a factor
// √2 for the variance from 2 vs 4 samples is generous; jumps of 3× were seen before).
TEST(Render, NoiseFigureFallsPassAfterPass) {
  test::SceneFixture fx;
  auto j = fx.scene;
  j["render"] = {{"integrator", "realtime"}, {"spp", 64}};
  const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
  std::vector<std::pair<int, double>> noise;
  render_scene(s, [&](const RenderProgress& p) {
    if (p.noise >= 0) noise.push_back({p.spp_done, p.noise});
  });
  ASSERT_EQ(noise.size(), 8u);
  for (std::size_t k = 1; k < noise.size(); ++k) {
    std::printf("%d spp: noise %.4f\n", noise[k].first, noise[k].second);
    EXPECT_LE(noise[k].second, noise[k - 1].second * std::sqrt(2.0)) << noise[k].first << " spp";
  }
  EXPECT_LT(noise.back().second, noise.front().second);
}

// Every channel of the layered EXR is finite, always: here the environment holds NaN, −inf and the
// largest finite float (3.4e38, which overflows as soon as it is scaled), the scene has a floor
// catcher and the path integrator. Every channel is read back and checked.
TEST(Render, EveryLayerIsFiniteAtTheExtremes) {
  test::SceneFixture fx;
  Image env(16, 8, 3, 0.5f);
  env.set_rgb(3, 1, Rgb(std::numeric_limits<float>::max(), 1, 1));
  env.set_rgb(9, 2, Rgb(std::nanf(""), -std::numeric_limits<float>::infinity(), 2));
  write_image(fx.dir.file("env.exr"), env);
  auto j = fx.scene;
  j["render"] = {{"integrator", "path"}, {"spp", 4}};
  j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  j["objects"][0]["translate"] = {0, 0.3, 0};
  j["output"] = {{"image", "out/c.exr"}, {"layers", "out/layers.exr"}};
  const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
  write_outputs(s, render_scene(s));
  auto in = OIIO::ImageInput::open(fx.dir.file("out/layers.exr"));
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> pixels(std::size_t(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
  ASSERT_EQ(spec.nchannels, 28);
  for (std::size_t i = 0; i < pixels.size(); ++i)
    ASSERT_TRUE(std::isfinite(pixels[i])) << "channel " << spec.channelnames[i % std::size_t(spec.nchannels)]
                                          << ", pixel " << i / std::size_t(spec.nchannels);
}

// The variance layer predicts the spread between renders with different seeds: for independent
// estimates a and b of one pixel, E[(a − b)²] = 2·Var(mean); averaged over the changed pixels. At
// 256 spp the layer is batch means over blocks of 16 samples (render/pixel_variance.h), an upper
// bound for scrambled Sobol points that errs high by less than the estimate of independent
// samples (0.24 of it already at 64 spp).
TEST(Layers, VariancePredictsTheSpreadAcrossSeeds) {
  test::SceneFixture fx;
  auto j = fx.scene;
  j["render"] = {{"integrator", "path"}, {"spp", 256}};
  j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  j["objects"] = {{{"mesh", "good_quad.obj"}, {"translate", {0, 0.3, 0}}}};
  SceneSpec spec = parse_scene_file(fx.write(j));
  const LoadedScene s = load_scene(spec);
  const RenderResult a = render_scene(s);
  LoadedScene s2 = load_scene(spec);
  s2.spec.render.seed = 99;
  const RenderResult b = render_scene(s2);
  double diff2 = 0, var = 0;
  int n = 0;
  for (int y = 0; y < a.layers.variance.height; ++y)
    for (int x = 0; x < a.layers.variance.width; ++x) {
      const float va = *a.layers.variance.at(x, y), vb = *b.layers.variance.at(x, y);
      if (va <= 0 && vb <= 0) continue;
      auto value = [&](const RenderLayers& l) {
        return luminance(Rgb(l.objects.rgb(x, y) + l.with_objects.rgb(x, y) - l.without_objects.rgb(x, y)));
      };
      const double d = value(a.layers) - value(b.layers);
      diff2 += d * d;
      var += va + vb;
      ++n;
    }
  ASSERT_GT(n, 100);
  // Never optimistic: the ratio of the observed spread to the predicted one may exceed 1 only by
  // its own sampling error, about √(2/n) relative for n pixels (a χ² with n degrees of freedom);
  // 4 of those. Not wasteful either: the estimate of independent samples, 0.24 of the spread at 64
  // spp and less at 256, fails the lower bound.
  std::printf("observed / predicted spread %.3f over %d pixels\n", diff2 / var, n);
  EXPECT_GT(diff2 / var, 0.4);
  EXPECT_LT(diff2 / var, 1 + 4 * std::sqrt(2.0 / n)) << "n = " << n;
  // Where the camera met the object: its normal (+Y, the quad faces up) and albedo in the layers.
  // A block keeps its albedo to 11 significant bits (render/pixel_blocks.h): half an ulp, 2^-11
  // relative, at each level of the pixel's tree of samples.
  const Vec2d uv = s.camera.project({0.5, 0.3, -0.5});
  EXPECT_NEAR(a.layers.normal.at(int(uv.x()), int(uv.y()))[1], 1.0f, 1e-4f);
  const double albedo_tolerance = 0.8 * std::ldexp(1.0, -kFeatureBits - 1) * (std::log2(256.0) + 1);
  EXPECT_NEAR(a.layers.albedo.at(int(uv.x()), int(uv.y()))[0], 0.8f, albedo_tolerance);
  EXPECT_GT(*a.layers.depth.at(int(uv.x()), int(uv.y())), 0.0f);
}

TEST(Layers, ProgressReportsSamplesAndNoisePerPass) {
  test::SceneFixture fx;
  auto j = fx.scene;
  j["render"] = {{"integrator", "path"}, {"spp", 16}};
  j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  j["objects"] = {{{"mesh", "good_quad.obj"}, {"translate", {0, 0.3, 0}}}};
  const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
  std::vector<RenderProgress> reports;
  const RenderResult r = render_scene(s, [&](const RenderProgress& p) {
    if (p.noise >= 0) reports.push_back(p);
  });
  ASSERT_EQ(reports.size(), 8u);  // 8 passes of 2 samples
  EXPECT_EQ(reports.back().spp_done, 16);
  EXPECT_DOUBLE_EQ(reports.back().noise, r.layers.mean_relative_noise);
  EXPECT_GT(reports[1].noise, reports.back().noise);  // more samples, less noise
}

}  // namespace
}  // namespace insitu
