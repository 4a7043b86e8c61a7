// The room's light loaded from shots: exposures into the photo's unit (light/environment.h).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>

#include "core/colour.h"
#include "light/environment.h"
#include "light/equirect.h"
#include "light/hdr_merge.h"
#include "scene/pipeline.h"
#include "test_util.h"

namespace insitu {
namespace {

// A scene with six constant shots in a temporary folder, with EXIF exposures.
struct ShotScene {
  test::TempDir dir;
  nlohmann::json scene;
  ShotScene(double photo_time, double shot_time, bool exif) {
    Exposure e_photo, e_shot;
    e_photo.time_s = photo_time;
    e_shot.time_s = shot_time;
    write_image(dir.file("photo.jpg"), Image(32, 24, 3, 0.5f), exif ? &e_photo : nullptr);
    nlohmann::json shots = {{"faced", "-z"}};
    for (const char* k : {"+x", "-x", "+z", "-z", "up", "down"}) {
      const std::string name = std::string("s") + (k[0] == '+' ? "p" : k[0] == '-' ? "n" : "") + k + ".jpg";
      write_image(dir.file(name), Image(16, 16, 3, 0.5f), exif ? &e_shot : nullptr);
      shots[k] = name;
    }
    scene = {{"photo", "photo.jpg"},
             {"camera", {{"eye", {0, 1, 0}}, {"look", {0, 1, -1}}, {"hfov_deg", 60}}},
             {"environment", {{"shots", shots}}}};
  }
  LoadedScene load(const nlohmann::json& j) const {
    return load_scene(parse_scene_file(dir.write("scene.json", j.dump())));
  }
};

// Shots at 1/30 s, photo at 1/120 s: the same pixel value means 4× the radiance in the shots'
// exposure, so in the photo's unit the cube is value × (1/120)/(1/30) = value / 4.
TEST(Exposure, ExifRatioBringsShotsIntoThePhotosUnit) {
  ShotScene s(1.0 / 120, 1.0 / 30, true);
  const LoadedScene l = s.load(s.scene);
  EXPECT_EQ(l.environment_info.exposure_source, "exif");
  // EXIF stores the times as rationals read back as float: relative 1e-4.
  const float expected = srgb_to_linear(float(std::lround(0.5 * 255)) / 255) / 4;
  EXPECT_NEAR(l.environment.texel(kPosX, 3, 3)[0], expected, 1e-4f * expected);
}

TEST(Exposure, FactorEstimateAndRequiredExif) {
  ShotScene s(1.0 / 120, 1.0 / 30, false);
  auto j = s.scene;
  j["environment"]["exposure"] = 2.0;
  const LoadedScene f = s.load(j);
  EXPECT_EQ(f.environment_info.exposure_source, "factor");
  EXPECT_NEAR(f.environment.texel(kNegY, 1, 1)[1], 2 * srgb_to_linear(128.0f / 255), 1e-6);
  // No EXIF: the estimate matches medians (here photo and shots are equal: factor 1).
  const LoadedScene e = s.load(s.scene);
  EXPECT_EQ(e.environment_info.exposure_source, "estimate");
  EXPECT_NEAR(e.environment_info.exposure_factor, 1.0, 1e-6);
  j["environment"]["exposure"] = "exif";
  try {
    s.load(j);
    FAIL();
  } catch (const InputError& err) {
    EXPECT_NE(err.what() + std::string(), std::string());
    EXPECT_NE(std::string(err.what()).find("no exposure time in its EXIF"), std::string::npos) << err.what();
  }
}

TEST(Exposure, FieldOfViewFromThe35mmFocalLength) {
  // 26 mm equivalent on a 4:3 shot: diagonal fov 2·atan(43.27/52) = 79.5°, horizontal
  // 2·atan(0.8·tan 39.76°) = 67.3°.
  test::TempDir dir;
  Exposure e;
  e.focal_35mm_mm = 26;
  write_image(dir.file("s.jpg"), Image(40, 30, 3, 0.5f), &e);
  const ImageFile f = read_image_file(dir.file("s.jpg"));
  ASSERT_TRUE(f.exposure.focal_35mm_mm.has_value());
  const double expected = rad_to_deg(2 * std::atan(0.8 * 43.2666 / 52));
  EXPECT_NEAR(expected, 67.3, 0.1);
  // Through a scene: every shot at 26 mm covers less than its face.
  ShotScene s(1.0 / 60, 1.0 / 60, true);
  for (const char* name : {"spx.jpg", "snx.jpg", "spz.jpg", "snz.jpg", "sup.jpg", "sdown.jpg"})
    write_image(s.dir.file(name), Image(40, 30, 3, 0.5f), &e);
  auto j = s.scene;
  j["environment"]["shots"]["+x"] = "spx.jpg";
  j["environment"]["shots"]["-x"] = "snx.jpg";
  j["environment"]["shots"]["+z"] = "spz.jpg";
  j["environment"]["shots"]["-z"] = "snz.jpg";
  j["environment"]["shots"]["up"] = "sup.jpg";
  j["environment"]["shots"]["down"] = "sdown.jpg";
  j["environment"]["exposure"] = 1.0;
  const LoadedScene l = s.load(j);
  // Covered: tan(33.65°) × 0.75·tan(33.65°)·... of the face: below 1.
  EXPECT_LT(l.environment_info.coverage[kPosX], 0.5);
  EXPECT_GT(l.environment_info.coverage[kPosX], 0.2);
}

TEST(Exposure, BracketsInTheSceneFile) {
  ShotScene s(1.0 / 60, 1.0 / 60, true);
  // The +x shot as three brackets of a gradient, times given in the scene.
  Image grad(16, 16, 3);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) grad.set_rgb(x, y, Rgb::Constant(0.02f * float(1 + x + 16 * y)));
  const std::vector<double> times = {0.25, 1.0, 4.0};
  nlohmann::json files = nlohmann::json::array();
  for (std::size_t b = 0; b < 3; ++b) {
    Image enc(16, 16, 3);
    for (std::size_t i = 0; i < enc.data.size(); ++i) enc.data[i] = linear_to_srgb(float(grad.data[i] * times[b]));
    const std::string name = "b" + std::to_string(b) + ".png";
    write_image(s.dir.file(name), enc);
    files.push_back(name);
  }
  auto j = s.scene;
  j["environment"]["shots"]["+x"] = {{"files", files}, {"times", times}};
  j["environment"]["exposure"] = 1.0;
  const LoadedScene l = s.load(j);
  EXPECT_TRUE(l.environment_info.response.has_value());
  j["environment"]["shots"]["+x"] = {{"files", files}, {"times", {1.0}}};
  EXPECT_THROW(s.load(j), InputError);
}

// The ceiling and floor shots may be keyed "up"/"down" (the scene file's words) or "+y"/"-y" (the
// axes, as the walls are keyed); messages and reports use "up"/"down".
TEST(ShotSpelling, UpDownAndAxisNamesAreTheSame) {
  ShotScene s(1.0 / 120, 1.0 / 120, false);
  auto j = s.scene;
  j["environment"]["shots"]["+y"] = j["environment"]["shots"]["up"];
  j["environment"]["shots"]["-y"] = j["environment"]["shots"]["down"];
  j["environment"]["shots"].erase("up");
  j["environment"]["shots"].erase("down");
  const SceneSpec by_axis = parse_scene_file(s.dir.write("scene.json", j.dump()));
  const SceneSpec by_word = parse_scene_file(s.dir.write("scene.json", s.scene.dump()));
  EXPECT_EQ(by_axis.environment.shots[kPosY].files, by_word.environment.shots[kPosY].files);
  EXPECT_EQ(by_axis.environment.shots[kNegY].files, by_word.environment.shots[kNegY].files);
  j["environment"]["shots"]["up"] = j["environment"]["shots"]["+y"];
  try {
    parse_scene_file(s.dir.write("scene.json", j.dump()));
    ADD_FAILURE() << "both up and +y accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("give 'up' or '+y', not both"), std::string::npos) << e.what();
  }
  EXPECT_STREQ(face_name(kPosY), "up");
  EXPECT_STREQ(face_name(kNegY), "down");
  const LoadedScene l = s.load(s.scene);
  EXPECT_EQ(render_report(l, RenderResult{})["environment"]["shots"][2]["face"], "up");
}

}  // namespace
}  // namespace insitu
