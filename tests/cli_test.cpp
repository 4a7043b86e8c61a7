#include <gtest/gtest.h>
#include <sys/wait.h>

#include <fstream>
#include <sstream>

#include "core/camera.h"
#include "scene/pipeline.h"
#include "cli_util.h"
#include "scene_fixture.h"

namespace insitu {
namespace {
using namespace test;

TEST(Cli, Version) {
  test::TempDir dir;
  const CliRun r = run_insitu(dir, "--version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, std::string("insitu ") + INSITU_VERSION + "\n");
}

TEST(Cli, HelpListsTheRenderVerb) {
  test::TempDir dir;
  const CliRun r = run_insitu(dir, "--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("render"), std::string::npos);
}

TEST(Cli, UsageErrorsAreOneLine) {
  test::TempDir dir;
  expect_one_line_error(run_insitu(dir, ""), "subcommand");
  expect_one_line_error(run_insitu(dir, "render"), "scene");
  expect_one_line_error(run_insitu(dir, "paint scene.json"), "");
  expect_one_line_error(run_insitu(dir, "render x.json --spp 0"), "spp");
  // A range a person can read (issue 46: --index -1 named the range 0 to a 309-digit double).
  for (const char* args : {"batch b.json --index -1", "batch b.json --per-task 0"}) {
    const CliRun r = run_insitu(dir, args);
    expect_one_line_error(r, "2147483647");
    EXPECT_LT(r.err.size(), 120u) << r.err;
  }
}

TEST(Cli, MissingSceneFile) {
  test::TempDir dir;
  expect_one_line_error(run_insitu(dir, dir.file("nope.json")), "");
  expect_one_line_error(run_insitu(dir, "render " + dir.file("nope.json")), "nope.json: file not found");
}

TEST(Cli, BadInputsExitTwoAndWriteNothing) {
  test::SceneFixture fx;
  std::filesystem::copy_file(test::test_data("bad_index_range.obj"), fx.dir.path() / "bad.obj");
  auto j = fx.scene;
  j["objects"][0]["mesh"] = "bad.obj";
  j["output"] = {{"image", "out/composite.png"}, {"layers", "out/layers.exr"}};
  const std::string scene = fx.write(j);
  expect_one_line_error(run_insitu(fx.dir, "render " + scene),
                        "$.objects[0].mesh: " + fx.dir.file("bad.obj") + ":4: face vertex index 7");
  EXPECT_FALSE(std::filesystem::exists(fx.dir.file("out/composite.png")));
  EXPECT_FALSE(std::filesystem::exists(fx.dir.file("out/layers.exr")));

  fx.dir.write("scene.json", "{ \"photo\": ");
  expect_one_line_error(run_insitu(fx.dir, "render " + fx.dir.file("scene.json")), "malformed JSON");

  const std::string good = fx.write();
  expect_one_line_error(run_insitu(fx.dir, "render " + good + " --integrator magic"), "unknown integrator 'magic'");
  expect_one_line_error(run_insitu(fx.dir, "render " + good + " -o out/x.bmpx"), "unsupported extension");
}

TEST(Cli, RendersAScene) {
  test::SceneFixture fx;
  const std::string scene = fx.write();
  const CliRun r = run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("c.png") + " --spp 2");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(fx.dir.file("c.png")));
  EXPECT_TRUE(std::filesystem::exists(fx.dir.file("c.layers.exr")));
  // The report beside the image.
  std::ifstream report(fx.dir.file("c.png.report.json"));
  ASSERT_TRUE(report.good());
  const nlohmann::json j = nlohmann::json::parse(report);
  EXPECT_EQ(j["render"]["spp"], 2);
  EXPECT_EQ(j["render"]["integrator"], "realtime");
  EXPECT_EQ(j["render"]["nonfinite_samples"], 0);
  EXPECT_GE(j["seconds"]["render"].get<double>(), 0.0);
  EXPECT_EQ(j["environment"]["exposure"], "none");
  // No temporary files are left behind.
  for (const auto& e : std::filesystem::recursive_directory_iterator(fx.dir.path()))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

// A scene file whose name is not UTF-8 (Linux allows any bytes) renders, and its report names it
// with U+FFFD for the bad byte. Before: the image written, then "internal error" (exit 1) and no
// report, as json::dump refused the name (issue 46).
TEST(Cli, ASceneFileNamedInAnotherEncodingRenders) {
  test::SceneFixture fx;
  const std::string latin1 = fx.dir.file("sc\xe8ne.json");  // "scène" in Latin-1
  std::filesystem::copy_file(fx.write(), latin1);
  const CliRun r = run_insitu(fx.dir, "render '" + latin1 + "' -o " + fx.dir.file("c.png") + " --spp 1");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(test::slurp(fx.dir.file("c.png.report.json")));
  EXPECT_NE(report.dump().find("sc\xef\xbf\xbdne.json"), std::string::npos) << report.dump();  // U+FFFD
}

// Writes points.json: seven points as a known camera of the fixture's photo size sees them, with
// v from the top edge, or from the bottom edge.
void write_known_points(const test::SceneFixture& fx, bool bottom_left) {
  const Camera truth = Camera::look_at({0.5, 2.0, 1.5}, {0.5, 0.0, -0.5}, {0, 1, 0}, 60, fx.width, fx.height);
  nlohmann::json pts = nlohmann::json::array();
  const Vec3d xyz[] = {{0, 0, 0},        {1, 0, 0},        {1, 0, -1},      {0, 0, -1},
                       {0.5, 0.5, -0.5}, {0.2, 0.8, -0.9}, {0.9, 0.3, -0.2}};
  for (const auto& p : xyz) {
    const Vec2d uv = truth.project(p);
    pts.push_back({{"uv", {uv.x(), bottom_left ? fx.height - uv.y() : uv.y()}}, {"xyz", {p.x(), p.y(), p.z()}}});
  }
  fx.dir.write("points.json", pts.dump());
}

TEST(Cli, CalibrateWritesACameraFileThatScenesRead) {
  test::SceneFixture fx;
  write_known_points(fx, false);
  const CliRun r =
      run_insitu(fx.dir, "calibrate --points " + fx.dir.file("points.json") + " --image " + fx.dir.file("photo.png") +
                             " -o " + fx.dir.file("camera.json") + " --vc " + fx.dir.file("camera.vc"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("model        f"), std::string::npos) << r.out;
  auto j = fx.scene;
  j["camera"] = {{"file", "camera.json"}};
  const CliRun render = run_insitu(fx.dir, "render " + fx.write(j) + " --spp 1");
  EXPECT_EQ(render.exit_code, 0) << render.err;
  EXPECT_TRUE(std::filesystem::exists(fx.dir.file("camera.vc")));
}

// The pixel origin is spelt the same on the command line and in the scene file; both spellings
// work in both places.
TEST(Cli, OriginSpellingsAgreeBetweenCliAndScene) {
  test::SceneFixture fx;
  write_known_points(fx, true);
  const std::string base = "calibrate --points " + fx.dir.file("points.json") + " --size 48 32 --origin ";
  const CliRun dash = run_insitu(fx.dir, base + "bottom-left"), underscore = run_insitu(fx.dir, base + "bottom_left");
  ASSERT_EQ(dash.exit_code, 0) << dash.err;
  ASSERT_EQ(underscore.exit_code, 0) << underscore.err;
  EXPECT_EQ(dash.out, underscore.out);
  EXPECT_NE(dash.out.find("residuals    RMS"), std::string::npos) << dash.out;
  expect_one_line_error(run_insitu(fx.dir, base + "bottom"), "top_left");
  for (const char* spelling : {"bottom_left", "bottom-left"}) {
    auto j = fx.scene;
    j["camera"] = {{"points", "points.json"}, {"origin", spelling}};
    const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
    EXPECT_LT(s.calibration->rms_px, 1e-3) << spelling;
  }
}

// --box: the uncertainty at an object's corners in the report and in camera.json, with the hint;
// a malformed box is a one-line error. --blender writes the camera's Blender script.
TEST(Cli, CalibrateReportsTheUncertaintyAtEachBox) {
  test::TempDir dir;
  const std::string demo = test::source_dir() + "/scenes/demo/";
  const std::string base = "calibrate --points " + demo + "points.json --image " + demo + "photo.jpg ";
  const CliRun r = run_insitu(dir, base + "--box sofa -0.15 0 -2.93 1.95 0.85 -1.77 -o " + dir.file("camera.json") +
                                       " --blender " + dir.file("cam.py"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(test::slurp(dir.file("cam.py")).find("data.lens = "), std::string::npos);  // blender_camera_test renders it
  EXPECT_NE(r.out.find("object       sofa: up to "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("hint         click next a floor point"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(test::slurp(dir.file("camera.json")));
  const auto& sofa = j.at("calibration").at("at_objects").at("objects").at(0);
  EXPECT_EQ(sofa.at("points").size(), 8u);
  EXPECT_GT(sofa.at("radius95_px").get<double>(), 0.0);
  expect_one_line_error(run_insitu(dir, base + "--box sofa 0 0 0 1 x 1"), "--box sofa: expected six finite numbers");
  expect_one_line_error(run_insitu(dir, base + "--box sofa 0 0 0 1 nan 1"), "--box sofa: expected six finite numbers");
  expect_one_line_error(run_insitu(dir, base + "--box sofa 2 0 0 1 1 1"), "--box sofa: each minimum");
}

TEST(Cli, CalibrateBadInputIsOneLine) {
  test::TempDir dir;
  dir.write("few.json", R"([{"uv": [1, 2], "xyz": [0, 0, 0]}])");
  expect_one_line_error(run_insitu(dir, "calibrate --points " + dir.file("few.json") + " --size 640 480"),
                        "few.json: 1 control point(s): calibration needs at least 5");
  expect_one_line_error(run_insitu(dir, "calibrate --points " + dir.file("few.json")), "--image");
  expect_one_line_error(run_insitu(dir, "calibrate --points " + dir.file("few.json") + " --size 640 480 --model g"),
                        "model");
  dir.write("nan.csv", "1,2,3,4,5\n1,2,nan,4,5\n");
  expect_one_line_error(run_insitu(dir, "calibrate --points " + dir.file("nan.csv") + " --size 640 480"), "nan.csv:2");
}

TEST(Cli, CubemapWritesEveryOutput) {
  test::SceneFixture fx;
  const CliRun r = run_insitu(fx.dir, "cubemap " + fx.write() + " -o " + fx.dir.file("cube") + " --irradiance-size 4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"cube.exr", "cube.png", "equirect.exr", "irradiance_gaussian.exr", "irradiance_sh9.exr",
                        "irradiance_exact.exr", "irradiance_exact.png"})
    EXPECT_TRUE(std::filesystem::exists(fx.dir.file(std::string("cube/") + f))) << f;
  // The strip holds the cube at its face size (the fixture's 16×8 equirect: 4), the irradiance
  // strip 4×24.
  EXPECT_EQ(read_image_size(fx.dir.file("cube/cube.exr")), std::make_pair(4, 24));
  EXPECT_EQ(read_image_size(fx.dir.file("cube/irradiance_sh9.exr")), std::make_pair(4, 24));
  expect_one_line_error(run_insitu(fx.dir, "cubemap " + fx.dir.file("none.exr") + " -o " + fx.dir.file("x")),
                        "none.exr: file not found");
}

TEST(Cli, IrradianceReportPrintsEveryMode) {
  test::SceneFixture fx;
  const CliRun r =
      run_insitu(fx.dir, "irradiance-report " + fx.dir.file("env.exr") + " --normals 16 --csv " + fx.dir.file("r.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* mode : {"| gaussian |", "| sh9 |", "| exact |"})
    EXPECT_NE(r.out.find(mode), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(fx.dir.file("r.csv")));
}

TEST(Cli, IrradianceIntegratorWithGaussianEqualsRealtime) {
  test::SceneFixture fx;
  const std::string scene = fx.write();
  ASSERT_EQ(run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("a.png")).exit_code, 0);
  ASSERT_EQ(run_insitu(fx.dir,
                       "render " + scene + " --integrator irradiance --irradiance gaussian -o " + fx.dir.file("b.png"))
                .exit_code,
            0);
  EXPECT_EQ(read_image_file(fx.dir.file("a.png")).stored.data, read_image_file(fx.dir.file("b.png")).stored.data);
  auto j = fx.scene;
  j["render"]["irradiance"] = "sh10";
  expect_one_line_error(run_insitu(fx.dir, "render " + fx.write(j)),
                        "$.render.irradiance: expected \"gaussian\", \"sh9\", \"exact\" or \"volume\"");
}

TEST(Cli, CompareWritesThePictureAndRejectsMismatchedImages) {
  test::TempDir dir;
  write_image(dir.file("a.png"), Image(16, 12, 3, 0.5f));
  write_image(dir.file("b.png"), Image(16, 12, 3, 0.25f));
  write_image(dir.file("c.png"), Image(8, 12, 3, 0.25f));
  const CliRun r =
      run_insitu(dir, "compare " + dir.file("a.png") + " " + dir.file("b.png") + " -o " + dir.file("d.png"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("| image | 192 |"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir.file("d.png")));
  expect_one_line_error(run_insitu(dir, "compare " + dir.file("a.png") + " " + dir.file("c.png")), "c.png: 8x12");
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  // A linear EXR against an 8-bit PNG: said, since the PNG is clipped and display-referred.
  write_image(dir.file("e.exr"), Image(16, 12, 3, 0.25f));
  const CliRun mixed = run_insitu(dir, "compare " + dir.file("e.exr") + " " + dir.file("b.png"));
  EXPECT_EQ(mixed.exit_code, 0) << mixed.err;
  EXPECT_NE(mixed.err.find("insitu: warning: " + dir.file("b.png") + " is a display-referred 8-bit image"),
            std::string::npos)
      << mixed.err;
}

TEST(Cli, TradeoffWritesTableCsvPlotAndAb) {
  test::SceneFixture fx;
  auto j = fx.scene;
  j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  j["objects"] = {{{"mesh", "good_quad.obj"}, {"translate", {0, 0.3, 0}}}};
  const CliRun r = run_insitu(fx.dir, "tradeoff " + fx.write(j) + " -o " + fx.dir.file("t") +
                                          " --ladder 1,4,32 --reference-spp 64 --noise-targets 0.5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"tradeoff.csv", "tradeoff.png", "ab.png"})
    EXPECT_TRUE(std::filesystem::exists(fx.dir.file(std::string("t/") + f))) << f;
  for (const char* mode : {"| realtime | 1 |", "| realtime | 16 |", "| irradiance/sh9 | 16 |", "| path | 4 |",
                           "| path adaptive 0.5 |", "| path/cosine only | 4 |", "| path denoised | 4 |"})
    EXPECT_NE(r.out.find(mode), std::string::npos) << r.out;
  // More samples, closer to the reference.
  std::ifstream csv(fx.dir.file("t/tradeoff.csv"));
  std::string line;
  double e1 = -1, e4 = -1, d4 = -1;
  while (std::getline(csv, line)) {
    // mode,spp,seconds,relative_rmse,rest_relative_rmse
    auto error_of = [&] { return std::stod(line.substr(line.find(',', line.find(',', line.find(',') + 1) + 1) + 1)); };
    if (line.rfind("path,1,", 0) == 0) e1 = error_of();
    if (line.rfind("path,4,", 0) == 0) e4 = error_of();
    if (line.rfind("path denoised,4,", 0) == 0) d4 = error_of();
  }
  // The denoised composite is nearer the reference than the noisy one it came from.
  EXPECT_GT(d4, 0);
  EXPECT_LT(d4, e4);
  EXPECT_GT(e1, e4);
  EXPECT_GT(e4, 0);
}

}  // namespace
}  // namespace insitu
