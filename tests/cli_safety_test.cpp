// No command overwrites one of its own inputs, or one output with another (issue 10, "destroys
// input"): each case exits 2 with one line naming both, and the input is byte-for-byte unchanged.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_util.h"
#include "core/output_paths.h"
#include "scene_fixture.h"

namespace insitu {
namespace {

using namespace test;
namespace fs = std::filesystem;

// Runs `args`, expects a refusal mentioning `what`, and that `kept` did not change.
void expect_refused(const TempDir& dir, const std::string& args, const std::string& kept, const std::string& what) {
  const std::string before = slurp(kept);
  ASSERT_FALSE(before.empty()) << kept;
  const CliRun r = run_insitu(dir, args);
  expect_one_line_error(r, what);
  EXPECT_EQ(slurp(kept), before) << kept << " changed";
}

void dir_points(const SceneFixture& fx) {
  fx.dir.write("p.json", R"([{"uv": [1, 2], "xyz": [0, 0, 0]}, {"uv": [3, 2], "xyz": [1, 0, 0]}])");
}

// A scene with a textured mesh and six shots, so that every kind of input exists.
struct SafetyScene : SceneFixture {
  SafetyScene() {
    write_image(dir.file("wood.png"), Image(4, 4, 3, 0.5f));
    dir.write("tex.mtl", "newmtl wood\nKd 1 1 1\nmap_Kd wood.png\n");
    dir.write("tex.obj",
              "mtllib tex.mtl\nusemtl wood\nv 0 0 0\nv 1 0 0\nv 1 0 -1\nvt 0 0\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3\n");
    nlohmann::json shots = {{"faced", "-z"}};
    for (const char* k : {"+x", "-x", "+z", "-z", "up", "down"}) {
      const std::string name = std::string("shot") +
                               (k[0] == '+'   ? "p"
                                : k[0] == '-' ? "n"
                                              : "") +
                               (k + (k[0] == '+' || k[0] == '-')) + ".png";
      write_image(dir.file(name), Image(8, 8, 3, 0.4f));
      shots[k] = name;
    }
    scene["environment"] = {{"shots", shots}};
    scene["objects"] = {{{"mesh", "tex.obj"}}};
  }
};

TEST(OutputSafety, RenderNeverReplacesThePhotoAShotOrATexture) {
  SafetyScene fx;
  const std::string scene = fx.write();
  const std::string photo = fx.dir.file("photo.png");
  expect_refused(fx.dir, "render " + scene + " -o " + photo, photo, "is the photo");
  // Through "..", and through a symlink: the same file.
  fs::create_directories(fx.dir.path() / "sub");
  expect_refused(fx.dir, "render " + scene + " -o " + fx.dir.file("sub/../photo.png"), photo, "is the photo");
  fs::create_symlink(photo, fx.dir.path() / "link.png");
  expect_refused(fx.dir, "render " + scene + " -o " + fx.dir.file("link.png"), photo, "is the photo");
  expect_refused(fx.dir, "render " + scene + " -o " + fx.dir.file("shotpx.png"), fx.dir.file("shotpx.png"),
                 "is shot +x");
  expect_refused(fx.dir, "render " + scene + " -o " + fx.dir.file("wood.png"), fx.dir.file("wood.png"),
                 "read by " + fx.dir.file("tex.obj"));
  auto j = fx.scene;
  j["environment"] = "env.exr";
  expect_refused(fx.dir, "render " + fx.write(j) + " -o " + fx.dir.file("env.exr"), fx.dir.file("env.exr"),
                 "is the environment");
  expect_refused(fx.dir, "render " + fx.write(j) + " --layers " + fx.dir.file("env.exr"), fx.dir.file("env.exr"),
                 "is the environment");
  // In the scene file too.
  j = fx.scene;
  j["output"] = {{"image", "photo.png"}};
  expect_refused(fx.dir, "render " + fx.write(j), photo, "is the photo");
}

TEST(OutputSafety, LayersAndImageAreNeverOneFile) {
  SafetyScene fx;
  auto j = fx.scene;
  j["output"] = {{"image", "out/c.exr"}, {"layers", "out/c.exr"}};
  const CliRun r = run_insitu(fx.dir, "render " + fx.write(j));
  expect_one_line_error(r, "is also the output image");
  EXPECT_FALSE(fs::exists(fx.dir.file("out/c.exr")));
  const CliRun cli =
      run_insitu(fx.dir, "render " + fx.write() + " -o " + fx.dir.file("d.exr") + " --layers " + fx.dir.file("d.exr"));
  expect_one_line_error(cli, "is also the output image");
}

TEST(OutputSafety, CalibrateAndCompareNeverReplaceTheirInputs) {
  SafetyScene fx;
  const std::string photo = fx.dir.file("photo.png"), points = fx.dir.file("points.json");
  fx.dir.write("points.json", R"([{"uv": [1, 2], "xyz": [0, 0, 0]}])");
  expect_refused(fx.dir, "calibrate --points " + points + " --image " + photo + " -o " + photo, photo, "is the photo");
  expect_refused(fx.dir, "calibrate --points " + points + " --size 48 32 --vc " + points, points,
                 "is the control points");
  expect_refused(fx.dir, "compare " + photo + " " + fx.dir.file("wood.png") + " -o " + photo, photo, "is image A");
  // cubemap writes DIR/cube.exr: an environment of that name in DIR is refused.
  fs::copy_file(fx.dir.file("env.exr"), fx.dir.file("cube.exr"));
  expect_refused(fx.dir, "cubemap " + fx.dir.file("cube.exr") + " -o " + fx.dir.path().string(),
                 fx.dir.file("cube.exr"), "is the environment argument");
}

// An output that names a directory is refused before any work, with the reason (it once said
// "cannot write: Success").
TEST(OutputSafety, OutputThatIsADirectory) {
  SceneFixture fx;
  fs::create_directories(fx.dir.path() / "d.png");
  expect_one_line_error(run_insitu(fx.dir, "render " + fx.write() + " -o " + fx.dir.file("d.png")),
                        "d.png: is a directory");
  fs::create_directories(fx.dir.path() / "c.json");
  dir_points(fx);
  expect_one_line_error(
      run_insitu(fx.dir, "calibrate --points " + fx.dir.file("p.json") + " --size 48 32 -o " + fx.dir.file("c.json")),
      "c.json: is a directory");
}

TEST(OutputSafety, SameFileByIdentity) {
  TempDir dir;
  dir.write("a.txt", "a");
  fs::create_directories(dir.path() / "x");
  fs::create_symlink(dir.file("a.txt"), dir.path() / "x" / "l.txt");
  EXPECT_TRUE(same_file(dir.file("a.txt"), dir.file("x/../a.txt")));
  EXPECT_TRUE(same_file(dir.file("a.txt"), dir.file("x/l.txt")));
  EXPECT_FALSE(same_file(dir.file("a.txt"), dir.file("b.txt")));
  EXPECT_TRUE(same_file(dir.file("new.txt"), dir.file("x/../new.txt")));  // neither exists yet
}

}  // namespace
}  // namespace insitu
