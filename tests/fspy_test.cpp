#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "calib/fspy.h"
#include "scene/pipeline.h"
#include "scene_fixture.h"
#include "test_util.h"

namespace insitu {
namespace {

// fSpy's export for a wide 1600 × 1200 image: relative focal length 1.5, principal point
// (0.05, −0.02) on the image plane, the camera at Blender (2, −5, 1.5) looking along Blender +Y
// with +Z up: camera-to-world columns x → (1, 0, 0), y → (0, 0, 1), z → (0, −1, 0).
nlohmann::json wide_export() {
  return {{"principalPoint", {{"x", 0.05}, {"y", -0.02}}},
          {"horizontalFieldOfView", 2 * std::atan(1 / 1.5)},
          {"verticalFieldOfView", 2 * std::atan(0.75 / 1.5)},
          {"relativeFocalLength", 1.5},
          {"cameraTransform", {{"rows", {{1, 0, 0, 2}, {0, 0, -1, -5}, {0, 1, 0, 1.5}, {0, 0, 0, 1}}}}},
          {"viewTransform", {{"rows", {{1, 0, 0, -2}, {0, 0, 1, -1.5}, {0, -1, 0, -5}, {0, 0, 0, 1}}}}},
          {"vanishingPoints", {{{"x", 1}, {"y", 0}}, {{"x", -1}, {"y", 0}}, {{"x", 0}, {"y", 1}}}},
          {"vanishingPointAxes", {"xPositive", "yPositive", "zPositive"}},
          {"imageWidth", 1600},
          {"imageHeight", 1200}};
}

// By hand: fx = fy = 1.5 · 1600/2 = 1200 px; cx = 800 + 0.05 · 800 = 840, cy = 600 + 0.02 · 800 = 616.
// In insitu's Y-up world the eye is (2, 1.5, 5), looking down −z. Blender's point (2.5, 5, 1.8) is
// insitu's (2.5, 1.8, −5): X_c = (0.5, −0.3, 10), so u = 1200 · 0.05 + 840 = 900, v = −36 + 616 = 580.
TEST(Fspy, WideImageCameraAsDerivedByHand) {
  test::TempDir dir;
  const Camera c = camera_from_fspy(dir.write("room.json", wide_export().dump()), 1600, 1200);
  EXPECT_NEAR(c.fx, 1200, 1e-9);
  EXPECT_NEAR(c.fy, 1200, 1e-9);
  EXPECT_NEAR(c.cx, 840, 1e-9);
  EXPECT_NEAR(c.cy, 616, 1e-9);
  EXPECT_LT((c.eye_world() - Vec3d(2, 1.5, 5)).norm(), 1e-12);
  EXPECT_LT((c.forward_world() - Vec3d(0, 0, -1)).norm(), 1e-12);
  EXPECT_LT((c.up_world() - Vec3d(0, 1, 0)).norm(), 1e-12);
  const Vec2d uv = c.project(Vec3d(2.5, 1.8, -5));
  EXPECT_NEAR(uv.x(), 900, 1e-9);
  EXPECT_NEAR(uv.y(), 580, 1e-9);
  // A photo resized to half keeps the same camera in its own pixels.
  const Camera half = camera_from_fspy(dir.file("room.json"), 800, 600);
  EXPECT_NEAR(half.project(Vec3d(2.5, 1.8, -5)).x(), 450, 1e-9);
}

// A tall image: the longer side (the height) spans [−1, 1], and fSpy's "horizontal" field of view
// 2·atan(1/f_rel) is across it. With f_rel = 1.5 on 1200 × 1600: fx = 1.5 · 800 = 1200 px and the
// true horizontal field of view 2·atan(600/1200) = 53.13°.
TEST(Fspy, TallImageFieldOfViewIsAcrossTheLongerSide) {
  test::TempDir dir;
  auto j = wide_export();
  j["imageWidth"] = 1200;
  j["imageHeight"] = 1600;
  j["principalPoint"] = {{"x", 0.0}, {"y", 0.1}};
  const Camera c = camera_from_fspy(dir.write("tall.json", j.dump()), 1200, 1600);
  EXPECT_NEAR(c.fx, 1200, 1e-9);
  EXPECT_NEAR(c.cx, 600, 1e-9);
  EXPECT_NEAR(c.cy, 800 - 0.1 * 800, 1e-9);
  EXPECT_NEAR(c.hfov_deg(), rad_to_deg(2 * std::atan(0.5)), 1e-9);
}

void expect_fspy_error(const nlohmann::json& j, int w, int h, const std::string& where, const std::string& what) {
  test::TempDir dir;
  const std::string path = dir.write("bad.json", j.dump());
  try {
    camera_from_fspy(path, w, h);
    ADD_FAILURE() << "expected an error at " << where;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), path + ":" + where) << e.what();
    EXPECT_NE(e.message().find(what), std::string::npos) << e.what();
  }
}

TEST(Fspy, BadExportsAreOneLineErrorsWithTheirPlace) {
  auto j = wide_export();
  expect_fspy_error(j, 1200, 1200, "$.imageWidth", "not the same aspect ratio");
  j = wide_export();
  j["cameraTransform"]["rows"][0][0] = 2;
  expect_fspy_error(j, 1600, 1200, "$.cameraTransform.rows", "not a rotation");
  j = wide_export();
  j["cameraTransform"]["rows"][3][2] = 1;
  expect_fspy_error(j, 1600, 1200, "$.cameraTransform.rows", "not a camera transform");
  j = wide_export();
  j["relativeFocalLength"] = 2.0;
  expect_fspy_error(j, 1600, 1200, "$.relativeFocalLength", "disagrees");
  j = wide_export();
  j.erase("principalPoint");
  expect_fspy_error(j, 1600, 1200, "$", "principalPoint");
  j = wide_export();
  j["horizontalFieldOfView"] = 4.0;  // radians: beyond 180°
  expect_fspy_error(j, 1600, 1200, "$.horizontalFieldOfView", "");
  j = wide_export();
  j["extra"] = 1;
  expect_fspy_error(j, 1600, 1200, "$.extra", "");
}

// "camera": {"fspy": "room.json"} in a scene.
TEST(Fspy, SceneReadsAnFspyCamera) {
  test::SceneFixture fx;
  auto e = wide_export();
  e["imageWidth"] = fx.width;
  e["imageHeight"] = fx.height;
  fx.dir.write("room.json", e.dump());
  auto j = fx.scene;
  j["camera"] = {{"fspy", "room.json"}};
  const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
  EXPECT_LT((s.camera.eye_world() - Vec3d(2, 1.5, 5)).norm(), 1e-12);
  EXPECT_NEAR(s.camera.fx, 1.5 * 0.5 * std::max(fx.width, fx.height), 1e-9);
}

// The demo's fspy.json (tools/make_demo.cpp, the inverse of camera_from_fspy) is the generator's
// camera: eye (1.7, 1.45, 2.5), look (−0.2, 0.45, −1.2), 62° across 640 px (scenes/demo/README.md).
TEST(Fspy, TheDemosExportIsTheGeneratorsCamera) {
  const Camera truth = Camera::look_at(Vec3d(1.7, 1.45, 2.5), Vec3d(-0.2, 0.45, -1.2), Vec3d(0, 1, 0), 62.0, 640, 480);
  const Camera cam = camera_from_fspy(test::source_dir() + "/scenes/demo/fspy.json", 640, 480);
  for (const Vec3d& p : {Vec3d(0.95, 0.2, -0.2), Vec3d(-2.5, 2.6, -3.0), Vec3d(2.5, 0.0, -3.0), Vec3d(-1.0, 0.0, 1.0)})
    EXPECT_LT((cam.project(p) - truth.project(p)).norm(), 1e-6) << p.transpose();
}

}  // namespace
}  // namespace insitu
