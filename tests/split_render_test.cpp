// Split stills (issue 17): `insitu render --samples A:B` parts merged by `insitu merge` give the
// image, the layers and the report of one render of all their samples, bit for bit, wherever the
// render was split; parts that do not make a whole, or a scene changed since, are refused with a
// one-line error and no output.
#include <gtest/gtest.h>

#include <filesystem>
#include <fmt/format.h>

#include "cli_util.h"
#include "exr_pixels.h"
#include "scene_fixture.h"

namespace insitu {
namespace {

using test::exr_pixels;
using test::run_insitu;
using test::SceneFixture;

// The path integrator with a catcher plane, at 24 spp (not a power of two) or 16 (one Sobol net):
// both are split below.
std::string split_scene(SceneFixture& fx, int spp) {
  auto j = fx.scene;
  j["render"] = {{"integrator", "path"}, {"spp", spp}};
  j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  return fx.write(j);
}

// Renders the parts of [0, spp) cut at `cuts` and merges them (in reverse order) into OUT.
std::string merge_of_parts(SceneFixture& fx, const std::string& scene, const std::vector<int>& cuts, int spp,
                           const std::string& name) {
  std::vector<int> edges{0};
  edges.insert(edges.end(), cuts.begin(), cuts.end());
  edges.push_back(spp);
  std::string parts;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    const std::string part = fx.dir.file(fmt::format("{}-{}.part", name, i));
    const auto r =
        run_insitu(fx.dir, fmt::format("render {} --samples {}:{} --part {}", scene, edges[i], edges[i + 1], part));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, part + "\n");
    parts = part + " " + parts;
  }
  const std::string out = fx.dir.file(name + ".exr");
  const auto r = run_insitu(fx.dir, "merge " + parts + "-o " + out);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return out;
}

TEST(SplitRender, MergedPartsAreBitIdenticalToOneRender) {
  SceneFixture fx;
  // Under the sanitizers one sample count: the merge's code is the same at both, and each count
  // starts 13 CLI processes (38 s sanitized in CI).
  for (int spp : test::kUnderAsan ? std::vector<int>{16} : std::vector<int>{24, 16}) {
    const std::string scene = split_scene(fx, spp);
    const std::string whole = fx.dir.file(fmt::format("whole{}.exr", spp));
    ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " -o " + whole).exit_code, 0);
    int k = 0;
    for (const std::vector<int>& cuts : std::vector<std::vector<int>>{{1}, {spp / 2}, {5, 6, 13}, {3, 7, spp - 1}}) {
      const std::string name = fmt::format("merged{}-{}", spp, k++);
      const std::string out = merge_of_parts(fx, scene, cuts, spp, name);
      ASSERT_FALSE(exr_pixels(whole).empty());
      EXPECT_TRUE(exr_pixels(out) == exr_pixels(whole)) << name;
      EXPECT_TRUE(exr_pixels(fx.dir.file(name + ".layers.exr")) ==
                  exr_pixels(fx.dir.file(fmt::format("whole{}.layers.exr", spp))))
          << name;
    }
  }
}

// `merge --denoise` denoises the merged composite as `render --denoise` does the whole render's:
// the same image bit for bit (the denoiser is deterministic), the layers as rendered, and the
// report's denoise seconds; without it the merge is not denoised.
TEST(SplitRender, AMergeDenoisesAsTheWholeRenderDoes) {
  SceneFixture fx;
  const std::string scene = split_scene(fx, 16);
  const std::string whole = fx.dir.file("whole.exr"), denoised = fx.dir.file("whole_d.exr");
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " -o " + whole).exit_code, 0);
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " --denoise -o " + denoised).exit_code, 0);
  ASSERT_FALSE(exr_pixels(whole) == exr_pixels(denoised)) << "the scene's render has noise to remove";
  const std::string a = fx.dir.file("a.part"), b = fx.dir.file("b.part"), out = fx.dir.file("m.exr");
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " --samples 0:5 --part " + a).exit_code, 0);
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " --samples 5:16 --part " + b).exit_code, 0);
  const auto r = run_insitu(fx.dir, "merge " + a + " " + b + " --denoise -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(exr_pixels(out) == exr_pixels(denoised));
  EXPECT_TRUE(exr_pixels(fx.dir.file("m.layers.exr")) == exr_pixels(fx.dir.file("whole_d.layers.exr")));
  const auto report = nlohmann::json::parse(test::slurp(fx.dir.file("m.exr.report.json")));
  EXPECT_TRUE(report["denoise"].is_object()) << report["denoise"].dump();
  ASSERT_EQ(run_insitu(fx.dir, "merge " + a + " " + b + " -o " + out).exit_code, 0);
  EXPECT_TRUE(exr_pixels(out) == exr_pixels(whole));
}

// A part of samples [A, B) merged alone (--allow-partial) is a render of those samples only: it
// differs from the whole, and its samples layer says B − A.
TEST(SplitRender, OnePartIsARenderOfItsSamples) {
  SceneFixture fx;
  const std::string scene = split_scene(fx, 16);
  const std::string part = fx.dir.file("p.part"), out = fx.dir.file("p.exr");
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " --samples 4:10 --part " + part).exit_code, 0);
  // Not all the samples: refused, naming the range no part has (issue 46: exit 0 and
  // "interrupted": false before), unless asked for.
  test::expect_one_line_error(run_insitu(fx.dir, "merge " + part + " -o " + out),
                              "samples 0:4 of the 16 spp are in no part");
  EXPECT_FALSE(std::filesystem::exists(out));
  ASSERT_EQ(run_insitu(fx.dir, "merge " + part + " -o " + out + " --allow-partial").exit_code, 0);
  const auto report = nlohmann::json::parse(test::slurp(fx.dir.file("p.exr.report.json")));
  EXPECT_EQ(report["render"]["interrupted"], true);
  EXPECT_EQ(report["render"]["spp"], 6) << report["render"].dump();
  EXPECT_EQ(report["render"]["spp_planned"], 16);
  const std::string whole = fx.dir.file("w.exr");
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " -o " + whole).exit_code, 0);
  EXPECT_FALSE(exr_pixels(out) == exr_pixels(whole));
}

TEST(SplitRender, PartsThatDoNotMakeAWholeAreRefused) {
  SceneFixture fx;
  const std::string scene = split_scene(fx, 16);
  int n = 0;
  auto part = [&](const std::string& range, const std::string& extra = "") {
    const std::string path = fx.dir.file(fmt::format("part{}.part", n++));
    EXPECT_EQ(run_insitu(fx.dir, "render " + scene + " --samples " + range + " --part " + path + extra).exit_code, 0);
    return path;
  };
  const std::string a = part("0:4"), b = part("4:8"), c = part("6:16"), d = part("9:16");
  const std::string out = fx.dir.file("m.exr");
  test::expect_one_line_error(run_insitu(fx.dir, "merge " + a + " " + b + " -o " + out), "samples 8:16 of the 16 spp");
  test::expect_one_line_error(run_insitu(fx.dir, "merge " + b + " -o " + out), "samples 0:4 of the 16 spp");
  test::expect_one_line_error(run_insitu(fx.dir, "merge " + a + " " + c + " " + b + " -o " + out), "they overlap");
  test::expect_one_line_error(run_insitu(fx.dir, "merge " + a + " " + b + " " + d + " -o " + out), "a gap");
  const std::string other = part("8:16", " --seed 5");
  test::expect_one_line_error(run_insitu(fx.dir, "merge " + a + " " + b + " " + other + " -o " + out),
                              "another scene, other inputs or other settings");
  test::expect_one_line_error(run_insitu(fx.dir, "merge " + a + " -o " + a), "");
  EXPECT_FALSE(std::filesystem::exists(out)) << "no output from a refused merge";
  // An input changed since the parts were rendered.
  const std::string e = part("8:16");
  auto j = nlohmann::json::parse(test::slurp(scene));
  j["camera"]["hfov_deg"] = 61;
  fx.write(j);
  test::expect_one_line_error(run_insitu(fx.dir, "merge " + a + " " + b + " " + e + " -o " + out), "other inputs");
  fx.dir.write("junk.part", "INSITUCK and then nothing");
  test::expect_one_line_error(run_insitu(fx.dir, "merge " + fx.dir.file("junk.part") + " -o " + out), "junk.part");
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(SplitRender, BadSampleRangesAreRefused) {
  SceneFixture fx;
  const std::string scene = split_scene(fx, 16);
  for (const char* bad : {"4", "4:", "a:b", "8:4", "4:4", "-1:3", "0:17", "0:16x"})
    test::expect_one_line_error(run_insitu(fx.dir, "render " + scene + " --samples " + std::string(bad)), "--samples");
  test::expect_one_line_error(run_insitu(fx.dir, "render " + scene + " --part " + fx.dir.file("x.part")), "--samples");
}

}  // namespace
}  // namespace insitu

namespace insitu {
namespace {

// Lean buffers (issue 50): a part of the demo room (640×480, room box, floor catcher) stores
// about 27 bytes per pixel for its one block (100 as the raw fields): ≤ 40, the goal. A range
// of 6 samples has two blocks a pixel (4 + 2), as a checkpoint between passes does: ≤ 64.
// The raw fields compressed as planes, without the XOR and round_block, were 39 for the first
// (docs/farm.md).
TEST(SplitRender, PartsAreLean) {
  SceneFixture fx;
  const std::string scene = test::source_dir() + "/scenes/demo/scene.json";
  for (const auto& [range, most] : {std::pair{"0:4", 40.0}, std::pair{"0:6", 64.0}}) {
    const std::string part = fx.dir.file("demo.part");
    ASSERT_EQ(
        run_insitu(fx.dir, fmt::format("render {} --spp 16 --samples {} --part {}", scene, range, part)).exit_code, 0);
    const double per_pixel = double(std::filesystem::file_size(part)) / (640.0 * 480.0);
    EXPECT_LE(per_pixel, most) << range;
    std::filesystem::remove(part);
  }
}

}  // namespace
}  // namespace insitu
