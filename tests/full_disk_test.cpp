// Writes that cannot lie (issue 46): a disk that fills up mid-write gives a one-line error naming
// the output, exit 2, no file under the output's name and no temporary left; a resume that cannot
// write its image keeps its checkpoint. The full disk is `ulimit -f` (the process's file-size
// limit: a write past it fails with EFBIG, as one past a full disk fails with ENOSPC). Before, a
// truncated PNG got its final name with exit 0, and a resume then deleted its checkpoint.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fmt/format.h>

#include "cli_util.h"
#include "render/checkpoint.h"
#include "scene/pipeline.h"
#include "scene/scene_file.h"
#include "scene_fixture.h"

namespace insitu {
namespace {

using test::SceneFixture;
namespace fs = std::filesystem;

// 16 blocks of the shell's ulimit (512 bytes in dash, 1024 in bash): below every image of a
// 160 × 120 noise photo (PNG about 57 kB, JPEG about 25 kB, EXR about 230 kB).
constexpr int kLimitBlocks = 16;

test::CliRun run_on_a_small_disk(const test::TempDir& dir, const std::string& args) {
  const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
  const int status =
      test::run_with_leak_check(fmt::format("ulimit -f {}; ", kLimitBlocks),
                                std::string(INSITU_BINARY) + " " + args + " < /dev/null > " + out + " 2> " + err, err);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, test::slurp(out), test::slurp(err)};
}

// The files in `folder` whose names start with '.' (the temporary names outputs are written under).
std::vector<std::string> hidden_files(const fs::path& folder) {
  std::vector<std::string> found;
  if (!fs::exists(folder)) return found;
  for (const auto& e : fs::directory_iterator(folder))
    if (e.path().filename().string().front() == '.') found.push_back(e.path().filename().string());
  return found;
}

SceneFixture noisy_scene() {
  SceneFixture fx(160, 120);
  fx.scene["render"] = {{"integrator", "realtime"}, {"spp", 2}};
  fx.write();
  return fx;
}

TEST(FullDisk, NoImageFormatGetsItsNameWhenTheDiskIsFull) {
  SceneFixture fx = noisy_scene();
  // The arguments, and the output written first (the layers come before the image).
  const std::string out = fx.dir.file("out");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"-o " + out + "/c.png --layers none", "c.png"},
      {"-o " + out + "/c.jpg --layers none", "c.jpg"},
      {"-o " + out + "/c.exr --layers none", "c.exr"},
      {"-o " + out + "/c.png --layers " + out + "/l.exr", "l.exr"}};
  for (const auto& [args, first] : cases) {
    fs::remove_all(out);
    const test::CliRun r = run_on_a_small_disk(fx.dir, "render " + fx.dir.file("scene.json") + " " + args);
    test::expect_one_line_error(r, first);
    for (const char* name : {"c.png", "c.jpg", "c.exr", "l.exr", "c.png.report.json"})
      EXPECT_FALSE(fs::exists(fx.dir.path() / "out" / name)) << args << ": " << name;
    EXPECT_TRUE(hidden_files(fx.dir.path() / "out").empty()) << args << ": a temporary file was left";
  }
}

// The outputs land together: when the last of them (the report) cannot take its name, the image
// and the layers written before it keep their old bytes, and no temporary is left. Before, the
// new layers and image were in place beside the old report.
TEST(FullDisk, OutputsLandTogetherOrNotAtAll) {
  SceneFixture fx = noisy_scene();
  SceneSpec spec = parse_scene_file(fx.dir.file("scene.json"));
  spec.output.image = fx.dir.file("out/c.png");
  spec.output.layers = fx.dir.file("out/c.layers.exr");
  const LoadedScene scene = load_scene(spec);
  const RenderResult r = render_scene(scene);
  fs::create_directories(fx.dir.path() / "out");
  fx.dir.write("out/c.png", "old image");
  fx.dir.write("out/c.layers.exr", "old layers");
  fs::create_directories(fx.dir.path() / "out/c.png.report.json/inside");  // a folder where the report goes
  EXPECT_THROW(write_outputs(scene, r), InputError);
  EXPECT_EQ(test::slurp(fx.dir.file("out/c.png")), "old image");
  EXPECT_EQ(test::slurp(fx.dir.file("out/c.layers.exr")), "old layers");
  EXPECT_TRUE(hidden_files(fx.dir.path() / "out").empty()) << "a temporary file was left";
  fs::remove_all(fx.dir.path() / "out/c.png.report.json");
  write_outputs(scene, r);  // with the way clear, all three
  EXPECT_NE(test::slurp(fx.dir.file("out/c.png")), "old image");
  EXPECT_NE(test::slurp(fx.dir.file("out/c.layers.exr")), "old layers");
  EXPECT_TRUE(fs::exists(fx.dir.path() / "out/c.png.report.json"));
}

TEST(FullDisk, AResumeThatCannotWriteKeepsItsCheckpoint) {
  SceneFixture fx = noisy_scene();
  const std::string image = fx.dir.file("out/c.png"), checkpoint = checkpoint_path(image);
  {  // a checkpoint after the first of 2 passes, as an interrupted `insitu render -o out/c.png` leaves it
    SceneSpec spec = parse_scene_file(fx.dir.file("scene.json"));
    spec.output.image = image;
    const LoadedScene scene = load_scene(spec);
    std::atomic<bool> stop{false};
    RenderState state;
    render_scene(scene, [&](const RenderProgress& p) { stop = stop || p.spp_done >= 1; }, {&stop, &state});
    ASSERT_EQ(state.spp_done, 1);
    fs::create_directories(fx.dir.path() / "out");
    write_checkpoint(checkpoint, state, render_fingerprint(scene));
  }
  const std::string saved = test::slurp(checkpoint);
  const std::string args = "render " + fx.dir.file("scene.json") + " -o " + image + " --layers none --resume";
  const test::CliRun full = run_on_a_small_disk(fx.dir, args);
  test::expect_one_line_error(full, "c.png");
  EXPECT_EQ(test::slurp(checkpoint), saved) << "the checkpoint was removed or changed";
  EXPECT_FALSE(fs::exists(image));
  EXPECT_FALSE(fs::exists(image + ".report.json"));
  // With room on the disk, the same resume finishes, and only then uses the checkpoint up.
  const test::CliRun room = test::run_insitu(fx.dir, args);
  EXPECT_EQ(room.exit_code, 0) << room.err;
  EXPECT_TRUE(fs::exists(image));
  EXPECT_FALSE(fs::exists(checkpoint));
}

}  // namespace
}  // namespace insitu
