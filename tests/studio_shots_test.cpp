// insitu studio's shots panel (issue 18, "Shots"): the six shots as the library uses them, and
// the edits of the scene file (turn, swap, faced wall) read back by the library's own parser.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "core/error.h"
#include "core/image.h"
#include "core/math.h"
#include "light/cubemap.h"
#include "scene/scene_file.h"
#include "studio/scene_edit.h"
#include "studio_fixture.h"

namespace insitu {
namespace {

using test::get_json;
using test::post;
using test::StudioFixture;
using test::TempDir;
using test::text_of;
namespace fs = std::filesystem;

TEST(StudioShots, ShowsEachShotAsTheLibraryAssemblesIt) {
  TempDir dir;
  StudioFixture studio(dir);
  const json v = get_json(studio.client(), "/api/shots");
  ASSERT_TRUE(v["error"].is_null()) << v.dump();
  EXPECT_EQ(v["faced"], "-z");
  ASSERT_EQ(v["shots"].size(), 6u);
  for (int f = 0; f < 6; ++f) {
    const json& s = v["shots"][std::size_t(f)];
    EXPECT_EQ(s["face"], face_name(f));
    EXPECT_EQ(s["key"], face_name(f));  // the demo names its shots by face
    EXPECT_EQ(s["files"].size(), 3u);   // brackets
    EXPECT_EQ(s["rotate_deg"], 0);
    // The demo's generator shoots square 90° shots (tools/make_demo.cpp): full coverage.
    EXPECT_EQ(s["width"], s["height"]);
    EXPECT_NEAR(s["hfov_deg"].get<double>(), 90.0, 1e-9);
    EXPECT_NEAR(s["coverage_percent"].get<double>(), 100.0, 1e-9);
    EXPECT_GE(s["clipped_percent"].get<double>(), 0.0);
  }
  // The preview: a PNG no larger than 320 px a side, of the shot's shape.
  auto c = studio.client();
  const auto r = c.Get("/api/shot/0.png");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200);
  const cv::Mat png =
      cv::imdecode(cv::Mat(1, int(r->body.size()), CV_8U, const_cast<char*>(r->body.data())), cv::IMREAD_COLOR);
  ASSERT_FALSE(png.empty());
  EXPECT_LE(std::max(png.cols, png.rows), 320);
  EXPECT_EQ(png.cols, png.rows);
  EXPECT_EQ(c.Get("/api/shot/6.png")->status, 404);
}

// The stitched view's PNG, decoded.
cv::Mat stitched(const StudioFixture& studio) {
  const auto r = studio.client().Get("/api/shots/stitched.png");
  if (!r || r->status != 200) return {};
  return cv::imdecode(cv::Mat(1, int(r->body.size()), CV_8U, const_cast<char*>(r->body.data())), cv::IMREAD_COLOR);
}

// The stitched view: the cross at 160 pixels a face, each shot outlined in its colour, and what no
// shot saw hatched. The demo's square 90° shots cover the sphere exactly: no gap, and the −z
// shot's frame is its square's edge (drawn last, on top). Narrowed to 60°, six square shots see
// 6 · 4 asin(sin² 30°) sr (a rectangular pyramid's solid angle) of 4π: the gap is 51.7 %, and a
// square's corner is hatched.
TEST(StudioShots, TheStitchedViewOutlinesEachShotAndHatchesWhatNoneSaw) {
  TempDir dir;
  StudioFixture studio(dir);
  const json v = get_json(studio.client(), "/api/shots");
  ASSERT_TRUE(v["error"].is_null()) << v.dump();
  EXPECT_LT(v["gap_percent"].get<double>(), 0.1);
  for (const json& s : v["shots"]) {
    EXPECT_EQ(s["outline"].get<std::string>().size(), 7u);
    EXPECT_TRUE(s.contains("registration") && s.contains("room_lines")) << s.dump();
  }
  cv::Mat png = stitched(studio);
  ASSERT_FALSE(png.empty());
  EXPECT_EQ(png.cols, 640);
  EXPECT_EQ(png.rows, 480);
  const std::string hex = v["shots"][5]["outline"];  // −z, "#rrggbb"; OpenCV's pixels are BGR
  const long rgb = std::strtol(hex.c_str() + 1, nullptr, 16);
  const cv::Vec3b edge = png.at<cv::Vec3b>(240, 319);
  EXPECT_EQ(edge, cv::Vec3b(uchar(rgb & 255), uchar((rgb >> 8) & 255), uchar(rgb >> 16)));

  json scene = json::parse(text_of(studio.folder() / "scene.json"));
  scene["environment"]["shots"]["hfov_deg"] = 60;
  std::ofstream(studio.folder() / "scene.json") << scene.dump(2);
  const json narrow = get_json(studio.client(), "/api/shots");
  const double seen = 6 * 4 * std::asin(std::pow(std::sin(deg_to_rad(30.0)), 2)) / (4 * kPi);
  EXPECT_NEAR(narrow["gap_percent"].get<double>(), 100 * (1 - seen), 1.0);
  png = stitched(studio);
  ASSERT_FALSE(png.empty());
  // The −z square's top-left corner (165, 165: (x + y) mod 8 < 3, a hatched diagonal) is 53° off
  // the −z axis and as far from −x and the ceiling: outside every 60° shot, tinted magenta.
  const cv::Vec3b corner = png.at<cv::Vec3b>(165, 165);
  EXPECT_GT(int(corner[2]), int(corner[1]) + 40);
  EXPECT_GT(int(corner[0]), int(corner[1]) + 40);
}

// Without a room box the render anchors the shots to the photo (light/photo_anchor.h), and the
// shots panel shows them as the render has them: each shot's photo_anchor, as in the render
// report. Where the camera cannot be had yet (two points clicked), the panel says why the photo did
// not anchor them. With the demo's room box the room's lines anchor instead.
TEST(StudioShots, WithoutARoomBoxTheShotsAreAnchoredToThePhotoAsRendered) {
  TempDir dir;
  StudioFixture studio(dir);
  const json boxed = get_json(studio.client(), "/api/shots");
  ASSERT_TRUE(boxed["error"].is_null()) << boxed.dump();
  EXPECT_FALSE(boxed.contains("photo_anchor_note"));
  for (const json& s : boxed["shots"]) EXPECT_TRUE(s["photo_anchor"].is_null()) << s.dump();

  json scene = json::parse(text_of(studio.folder() / "scene.json"));
  scene["environment"].erase("room_box");
  std::ofstream(studio.folder() / "scene.json") << scene.dump(2);
  const json open = get_json(studio.client(), "/api/shots");
  ASSERT_TRUE(open["error"].is_null()) << open.dump();
  EXPECT_FALSE(open.contains("photo_anchor_note")) << open["photo_anchor_note"];
  for (const json& s : open["shots"]) {
    ASSERT_TRUE(s["photo_anchor"].is_object()) << s.dump();
    EXPECT_TRUE(s["photo_anchor"].contains("anchored") && s["photo_anchor"].contains("matches")) << s.dump();
    EXPECT_EQ(s["room_lines"]["axes"], "vertical") << s.dump();
  }
  EXPECT_TRUE(stitched(studio).data);

  // Two clicks so far: too few for a camera.
  json points = json::parse(text_of(studio.folder() / "points.json"));
  points.erase(points.begin() + 2, points.end());
  std::ofstream(studio.folder() / "two_points.json") << points.dump(2);
  scene["camera"]["points"] = "two_points.json";
  std::ofstream(studio.folder() / "scene.json") << scene.dump(2);
  const json uncalibrated = get_json(studio.client(), "/api/shots");
  ASSERT_TRUE(uncalibrated["error"].is_null()) << uncalibrated.dump();
  ASSERT_TRUE(uncalibrated.contains("photo_anchor_note")) << uncalibrated.dump();
  EXPECT_NE(uncalibrated["photo_anchor_note"].get<std::string>().find("$.camera.points"), std::string::npos)
      << uncalibrated["photo_anchor_note"];
  for (const json& s : uncalibrated["shots"]) EXPECT_TRUE(s["photo_anchor"].is_null()) << s.dump();
}

// Turning a shot writes rotate_deg into the scene file (a bracket list becomes an object), the
// library reads the turn, and a page holding the old version is refused without a write.
TEST(StudioShots, TurningAShotRewritesTheSceneFileAndAStalePageIsRefused) {
  TempDir dir;
  StudioFixture studio(dir);
  const fs::path scene = studio.folder() / "scene.json";
  const json before = get_json(studio.client(), "/api/shots");
  const auto [code, reply] = post(studio.client(), "/api/shots",
                                  {{"version", before["version"]}, {"op", "turn"}, {"key", "+x"}, {"by_deg", 90}});
  ASSERT_EQ(code, 200) << reply.dump();
  const json file = json::parse(text_of(scene));
  EXPECT_EQ(file["environment"]["shots"]["+x"]["rotate_deg"], 90);
  EXPECT_EQ(file["environment"]["shots"]["+x"]["files"].size(), 3u);
  EXPECT_EQ(parse_scene_file(scene.string()).environment.shots[kPosX].rotate_deg, 90);
  EXPECT_NE(reply["version"], before["version"]);
  // The page's view of it.
  const json after = get_json(studio.client(), "/api/shots");
  EXPECT_EQ(after["shots"][0]["rotate_deg"], 90);
  // A second tab, still at the first version: refused, and the file is as the first left it.
  const std::string text = text_of(scene);
  const auto [stale, stale_reply] =
      post(studio.client(), "/api/shots", {{"version", before["version"]}, {"op", "turn"}, {"key", "-x"}});
  EXPECT_EQ(stale, 409) << stale_reply.dump();
  EXPECT_EQ(text_of(scene), text);
  // Three more quarters bring it back, and the key goes away.
  std::string version = after["version"];
  for (int k = 0; k < 3; ++k) {
    const auto [c2, r2] = post(studio.client(), "/api/shots", {{"version", version}, {"op", "turn"}, {"key", "+x"}});
    ASSERT_EQ(c2, 200) << r2.dump();
    version = r2["version"];
  }
  EXPECT_FALSE(json::parse(text_of(scene))["environment"]["shots"]["+x"].contains("rotate_deg"));
}

TEST(StudioShots, SwappingTwoShotsTradesTheirFilesAndTheFacedWallIsSet) {
  TempDir dir;
  StudioFixture studio(dir);
  const fs::path scene = studio.folder() / "scene.json";
  const json old_file = json::parse(text_of(scene));
  json v = get_json(studio.client(), "/api/shots");
  auto [code, reply] =
      post(studio.client(), "/api/shots", {{"version", v["version"]}, {"op", "swap"}, {"a", "+x"}, {"b", "-z"}});
  ASSERT_EQ(code, 200) << reply.dump();
  const SceneSpec spec = parse_scene_file(scene.string());
  EXPECT_EQ(fs::path(spec.environment.shots[kPosX].files[1]).filename(), "north.jpg");
  EXPECT_EQ(fs::path(spec.environment.shots[kNegZ].files[1]).filename(), "east.jpg");
  // Nothing else changed.
  json expect = old_file;
  std::swap(expect["environment"]["shots"]["+x"], expect["environment"]["shots"]["-z"]);
  EXPECT_EQ(json::parse(text_of(scene)), expect);
  std::tie(code, reply) =
      post(studio.client(), "/api/shots", {{"version", reply["version"]}, {"op", "faced"}, {"wall", "+x"}});
  ASSERT_EQ(code, 200) << reply.dump();
  EXPECT_EQ(parse_scene_file(scene.string()).environment.faced_face, kPosX);
  // Refused with the reason, and nothing written: a floor as the faced wall, an unknown shot.
  const std::string text = text_of(scene);
  for (const json& bad : {json{{"op", "faced"}, {"wall", "down"}}, json{{"op", "swap"}, {"a", "+x"}, {"b", "sideways"}},
                          json{{"op", "spin"}}, json{{"op", "turn"}, {"key", "faced"}}}) {
    json body = bad;
    body["version"] = reply["version"];
    const auto [c2, r2] = post(studio.client(), "/api/shots", body);
    EXPECT_EQ(c2, 400) << bad.dump();
    EXPECT_FALSE(r2["what"].get<std::string>().empty());
  }
  EXPECT_EQ(text_of(scene), text);
}

// A shot that cannot be read is named in its own cell; a scene that does not parse is the view's
// error, with the key that caused it.
TEST(StudioShots, ErrorsAreNextToTheShotOrTheKeyThatCausedThem) {
  TempDir dir;
  StudioFixture studio(dir);
  std::ofstream(studio.folder() / "shots/west.jpg", std::ios::trunc) << "not a jpeg";
  const json v = get_json(studio.client(), "/api/shots");
  ASSERT_TRUE(v["error"].is_null()) << v.dump();
  const json& west = v["shots"][std::size_t(kNegX)];
  ASSERT_FALSE(west["error"].is_null()) << v.dump();
  EXPECT_NE(west["error"]["where"].get<std::string>().find("west.jpg"), std::string::npos) << west.dump();
  EXPECT_TRUE(v["shots"][std::size_t(kPosX)]["error"].is_null());
  fs::remove(studio.folder() / "shots/floor.jpg");
  const json v2 = get_json(studio.client(), "/api/shots");
  ASSERT_FALSE(v2["error"].is_null());
  EXPECT_NE(v2["error"]["where"].get<std::string>().find("$.environment.shots.down"), std::string::npos) << v2.dump();
}

// A scene lit by one image says which kind: an 8-bit panorama (read as one single shot, its clipped
// light recovered) is not an HDR image. The header alone decides; an unreadable one is the error.
TEST(StudioShots, AnImageEnvironmentIsNamedByItsKind) {
  TempDir dir;
  StudioFixture studio(dir);
  const fs::path scene = studio.folder() / "scene.json";
  json j = json::parse(std::ifstream(scene));
  const auto lit_by = [&](const std::string& image) {
    j["environment"] = {{"image", image}};
    std::ofstream(scene, std::ios::trunc) << j.dump();
    return get_json(studio.client(), "/api/shots");
  };
  Image sky(64, 32, 3, 0.5f);
  write_image((studio.folder() / "pano.jpg").string(), sky);
  write_image((studio.folder() / "sky.exr").string(), sky);
  const json pano = lit_by("pano.jpg"), hdr = lit_by("sky.exr");
  EXPECT_EQ(pano["image"], "pano.jpg");
  EXPECT_EQ(pano["image_kind"], "8-bit panorama") << pano.dump();
  EXPECT_EQ(hdr["image_kind"], "HDR image") << hdr.dump();
  std::ofstream(studio.folder() / "broken.jpg") << "not a jpeg";
  const json broken = lit_by("broken.jpg");
  ASSERT_FALSE(broken["error"].is_null()) << broken.dump();
  EXPECT_NE(broken["error"]["where"].get<std::string>().find("broken.jpg"), std::string::npos) << broken.dump();
}

// The edits on their own, on text: every form of a shot turns, order and other keys are kept.
TEST(StudioShots, SceneEditsKeepEverythingElse) {
  const std::string text = R"({"photo": "p.jpg", "environment": {"shots": {"+x": "a.jpg", "-x": ["b1.jpg", "b2.jpg"],
    "+z": {"file": "c.jpg", "hfov_deg": 70}, "-z": "d.jpg", "up": "e.jpg", "down": "f.jpg", "faced": "-z"}}, "render": {"spp": 4}})";
  const json turned =
      json::parse(turn_shot(turn_shot(turn_shot(text, "s.json", "+x", 90), "s.json", "-x", 270), "s.json", "+z", -90));
  EXPECT_EQ(turned["environment"]["shots"]["+x"], json({{"file", "a.jpg"}, {"rotate_deg", 90}}));
  EXPECT_EQ(turned["environment"]["shots"]["-x"], json({{"files", {"b1.jpg", "b2.jpg"}}, {"rotate_deg", 270}}));
  EXPECT_EQ(turned["environment"]["shots"]["+z"], json({{"file", "c.jpg"}, {"hfov_deg", 70}, {"rotate_deg", 270}}));
  // Keys stay in the file's order (the reader's json sorts them; the text must not).
  const std::string swapped = swap_shots(text, "s.json", "up", "down");
  EXPECT_LT(swapped.find("\"photo\""), swapped.find("\"environment\""));
  EXPECT_LT(swapped.find("\"environment\""), swapped.find("\"render\""));
  EXPECT_EQ(json::parse(swapped)["environment"]["shots"]["up"], "f.jpg");
  try {
    swap_shots(R"({"environment": "sky.exr"})", "s.json", "up", "down");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "s.json:$.environment");
  }
  EXPECT_THROW(turn_shot(text, "s.json", "+x", 45), InputError);
  EXPECT_THROW(turn_shot("{\"a\": 1, \"a\": 2}", "s.json", "+x", 90), InputError);  // the reader's own check
}

}  // namespace
}  // namespace insitu
