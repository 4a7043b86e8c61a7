// insitu render: where its outputs go, and what it says of options that have no effect.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "exr_pixels.h"
#include "render/render.h"
#include "scene/spec.h"
#include "scene_fixture.h"

namespace insitu {
namespace {

using namespace test;
namespace fs = std::filesystem;

nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(slurp(path)); }

// A quick `-o test.png` leaves the final render's layers and report alone: the layers and the
// report follow -o. Two formats of one stem keep their own reports.
TEST(CliRender, OutputMovesTheLayersAndReportWithIt) {
  SceneFixture fx;
  auto j = fx.scene;
  j["output"] = {{"image", "out/final.png"}, {"layers", "out/final.exr"}};
  const std::string scene = fx.write(j);
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene).exit_code, 0);
  const std::string final_layers = slurp(fx.dir.file("out/final.exr"));
  const std::string final_report = slurp(fx.dir.file("out/final.png.report.json"));
  ASSERT_FALSE(final_layers.empty());

  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("x.png") + " --spp 1").exit_code, 0);
  EXPECT_TRUE(fs::exists(fx.dir.file("x.layers.exr")));
  EXPECT_TRUE(fs::exists(fx.dir.file("x.png.report.json")));
  EXPECT_EQ(slurp(fx.dir.file("out/final.exr")), final_layers);
  EXPECT_EQ(slurp(fx.dir.file("out/final.png.report.json")), final_report);

  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("x.exr") + " --spp 2").exit_code, 0);
  EXPECT_EQ(read_json(fx.dir.file("x.png.report.json"))["render"]["spp"], 1);
  EXPECT_EQ(read_json(fx.dir.file("x.exr.report.json"))["render"]["spp"], 2);
}

TEST(CliRender, LayersOptionNamesOrDisablesTheLayers) {
  SceneFixture fx;
  const std::string scene = fx.write();
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("a.png") + " --layers none").exit_code, 0);
  EXPECT_TRUE(fs::exists(fx.dir.file("a.png")));
  EXPECT_FALSE(fs::exists(fx.dir.file("a.layers.exr")));
  EXPECT_FALSE(fs::exists(fx.dir.file("out/layers.exr")));
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("b.png") + " --layers " + fx.dir.file("l.exr"))
                .exit_code,
            0);
  EXPECT_TRUE(fs::exists(fx.dir.file("l.exr")));
  EXPECT_FALSE(fs::exists(fx.dir.file("b.layers.exr")));
  expect_one_line_error(run_insitu(fx.dir, "render " + scene + " --layers " + fx.dir.file("l.png")),
                        "use .exr, or none");
  auto j = fx.scene;
  j["output"] = {{"image", "out/c.png"}, {"layers", "none"}};
  ASSERT_EQ(run_insitu(fx.dir, "render " + fx.write(j)).exit_code, 0);
  EXPECT_FALSE(fs::exists(fx.dir.file("out/layers.exr")));
  // Without layers only the image is made, from the same floats: the same file, PNG or EXR.
  EXPECT_EQ(slurp(fx.dir.file("a.png")), slurp(fx.dir.file("b.png")));
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("d.exr") + " --layers none").exit_code, 0);
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("e.exr")).exit_code, 0);
  ASSERT_FALSE(test::exr_pixels(fx.dir.file("d.exr")).empty());
  EXPECT_TRUE(test::exr_pixels(fx.dir.file("d.exr")) == test::exr_pixels(fx.dir.file("e.exr")));
}

// Options that the output or the integrator does not use: a warning naming them, and the report
// says what was really done. The EXR is the same as without the option.
TEST(CliRender, OptionsWithoutEffectAreWarnedAndReportedAsDone) {
  SceneFixture fx;
  const std::string scene = fx.write();
  const CliRun plain = run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("p.exr"));
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(plain.err.find("warning"), std::string::npos) << plain.err;
  const CliRun r =
      run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("r.exr") + " --tonemap reinhard --key 0.3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("insitu: warning: output.tonemap: has no effect"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("insitu: warning: output.tonemap.key: has no effect"), std::string::npos) << r.err;
  EXPECT_EQ(read_json(fx.dir.file("r.exr.report.json"))["tonemap"], "none");
  EXPECT_EQ(read_image_file(fx.dir.file("r.exr")).stored.data, read_image_file(fx.dir.file("p.exr")).stored.data);

  const CliRun key = run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("k.png") + " --key 2");
  EXPECT_NE(key.err.find("output.tonemap.key: has no effect with the photo tone map"), std::string::npos) << key.err;
  const CliRun reinhard =
      run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("k2.png") + " --tonemap reinhard --key 2");
  EXPECT_EQ(reinhard.err.find("warning"), std::string::npos) << reinhard.err;
  EXPECT_EQ(read_json(fx.dir.file("k2.png.report.json"))["tonemap"], "reinhard");

  const CliRun irr =
      run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("i.png") + " --integrator path --irradiance sh9");
  EXPECT_NE(irr.err.find("render.irradiance: has no effect: the path integrator"), std::string::npos) << irr.err;
  EXPECT_TRUE(read_json(fx.dir.file("i.png.report.json"))["render"]["irradiance"].is_null());
  const CliRun used = run_insitu(
      fx.dir, "render " + scene + " -o " + fx.dir.file("j.png") + " --integrator irradiance --irradiance sh9");
  EXPECT_EQ(used.err.find("warning"), std::string::npos) << used.err;
  EXPECT_EQ(read_json(fx.dir.file("j.png.report.json"))["render"]["irradiance"], "sh9");

  auto j = fx.scene;
  j["render"]["max_depth"] = 3;  // the fixture renders with realtime
  EXPECT_NE(run_insitu(fx.dir, "render " + fx.write(j)).err.find("render.max_depth: has no effect"), std::string::npos);
}

// A quad 0.3 m over a floor plane, rendered by path at `spp`: something for the denoiser.
nlohmann::json quad_over_floor(const SceneFixture& fx, int spp) {
  auto j = fx.scene;
  j["render"] = {{"integrator", "path"}, {"spp", spp}};
  j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  j["objects"] = {{{"mesh", "good_quad.obj"}, {"translate", {0, 0.3, 0}}}};
  return j;
}

// --denoise (and the scene's "denoise"): the PNG keeps the photo's bytes wherever the render left
// the pixel and the pixels within 2 of it untouched (no coverage, W = N: the layers say which),
// changes the others, and the report says it was done; the layers stay as rendered.
TEST(CliRender, DenoiseKeepsThePhotosUntouchedPixelsAndSaysSo) {
  SceneFixture fx;
  auto j = quad_over_floor(fx, 4);
  const std::string scene = fx.write(j);
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("raw.png")).exit_code, 0);
  const CliRun d = run_insitu(fx.dir, "render " + scene + " --denoise -o " + fx.dir.file("d.png"));
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_TRUE(read_json(fx.dir.file("raw.png.report.json"))["denoise"].is_null());
  EXPECT_GE(read_json(fx.dir.file("d.png.report.json"))["denoise"]["seconds"].get<double>(), 0.0);
  EXPECT_TRUE(exr_pixels(fx.dir.file("raw.layers.exr")) != exr_pixels(fx.dir.file("d.layers.exr")));  // composite
  const ImageFile photo = read_image_file(fx.dir.file("photo.png"));
  const ImageFile raw = read_image_file(fx.dir.file("raw.png")), denoised = read_image_file(fx.dir.file("d.png"));
  const std::string layers = fx.dir.file("d.layers.exr");
  const std::vector<float> alpha = exr_channel(layers, "objects.A");
  std::vector<std::vector<float>> with, without;
  for (const char* c : {"R", "G", "B"})
    with.push_back(exr_channel(layers, std::string("with.") + c)),
        without.push_back(exr_channel(layers, std::string("without.") + c));
  const int width = photo.stored.width;
  ASSERT_EQ(alpha.size(), std::size_t(width) * photo.stored.height);
  const int height = photo.stored.height;
  auto touched = [&](int x, int y) {
    const std::size_t i = std::size_t(y) * width + x;
    bool t = alpha[i] != 0;
    for (int c = 0; c < 3; ++c) t |= with[c].at(i) != without[c].at(i);
    return t;
  };
  auto near_touched = [&](int x, int y) {
    for (int yy = std::max(0, y - 2); yy <= std::min(height - 1, y + 2); ++yy)
      for (int xx = std::max(0, x - 2); xx <= std::min(width - 1, x + 2); ++xx)
        if (touched(xx, yy)) return true;
    return false;
  };
  long untouched = 0, changed = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const bool near = near_touched(x, y);
      for (int c = 0; c < 3; ++c) {
        if (!near) {
          EXPECT_EQ(denoised.stored.at(x, y)[c], photo.stored.at(x, y)[c]) << x << "," << y;
        }
        changed += denoised.stored.at(x, y)[c] != raw.stored.at(x, y)[c];
      }
      untouched += !near;
    }
  EXPECT_GT(untouched, 0);
  EXPECT_GT(changed, 0);
  j["denoise"] = "yes";
  expect_one_line_error(run_insitu(fx.dir, "render " + fx.write(j)), "$.denoise");
}

// A noise-free integrator's image is left as it is, and the user is told the flag did nothing.
TEST(CliRender, DenoiseLeavesANoiseFreeIntegratorAlone) {
  SceneFixture fx;
  auto j = fx.scene;
  j["render"] = {{"integrator", "realtime"}, {"spp", 1}};
  j["objects"] = {{{"mesh", "good_quad.obj"}, {"translate", {0, 0.3, 0}}}};
  const std::string scene = fx.write(j);
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("raw.png")).exit_code, 0);
  const CliRun d = run_insitu(fx.dir, "render " + scene + " --denoise -o " + fx.dir.file("d.png"));
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_NE(d.err.find("denoise: has no effect: the realtime integrator is not Monte Carlo"), std::string::npos)
      << d.err;
  EXPECT_TRUE(read_json(fx.dir.file("d.png.report.json"))["denoise"].is_null());
  EXPECT_TRUE(exr_pixels(fx.dir.file("raw.layers.exr")) == exr_pixels(fx.dir.file("d.layers.exr")));
}

// One sample a pixel gives the denoiser no noise to weigh by: it is skipped, the image is the one
// rendered without it, bit for bit, and the report says why.
TEST(CliRender, DenoiseAtOneSampleIsSkippedAndSaysSo) {
  SceneFixture fx;
  auto j = quad_over_floor(fx, 1);
  const std::string scene = fx.write(j);
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("raw.png")).exit_code, 0);
  const CliRun d = run_insitu(fx.dir, "render " + scene + " --denoise -o " + fx.dir.file("d.png"));
  ASSERT_EQ(d.exit_code, 0) << d.err;
  const nlohmann::json report = read_json(fx.dir.file("d.png.report.json"))["denoise"];
  EXPECT_NE(report.value("skipped", "").find("no pixel has two samples"), std::string::npos) << report;
  EXPECT_EQ(slurp(fx.dir.file("raw.png")), slurp(fx.dir.file("d.png")));
  EXPECT_TRUE(exr_pixels(fx.dir.file("raw.layers.exr")) == exr_pixels(fx.dir.file("d.layers.exr")));
  // Two samples: denoised.
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " --spp 2 --denoise -o " + fx.dir.file("d2.png")).exit_code, 0);
  EXPECT_GE(read_json(fx.dir.file("d2.png.report.json"))["denoise"]["seconds"].get<double>(), 0.0);
}

// --help shows the defaults, and every verb accepts the same seed range.
TEST(CliRender, HelpShowsDefaults) {
  TempDir dir;
  const CliRun render = run_insitu(dir, "render --help");
  EXPECT_NE(render.out.find("[default: the scene's render.spp, else 16]"), std::string::npos) << render.out;
  const CliRun tradeoff = run_insitu(dir, "tradeoff --help");
  EXPECT_NE(tradeoff.out.find("comma-separated"), std::string::npos) << tradeoff.out;
  EXPECT_NE(tradeoff.out.find("1024"), std::string::npos) << tradeoff.out;  // --reference-spp's default
  const CliRun cubemap = run_insitu(dir, "cubemap --help");
  EXPECT_NE(cubemap.out.find("32"), std::string::npos) << cubemap.out;  // --irradiance-size's default
  const std::string max_seed = std::to_string(kMaxSeed - 1000);
  EXPECT_NE(tradeoff.out.find(max_seed), std::string::npos) << tradeoff.out;
  EXPECT_NE(render.out.find(std::to_string(kMaxSeed)), std::string::npos) << render.out;
}

}  // namespace
}  // namespace insitu
