// What determined the light, end to end (scene/light_recovery.h): a scene of six 8-bit shots, one
// with a clipped lamp, is fitted by default and says so in its report and in `insitu cubemap`;
// environment.inverse_lighting false leaves the lower bound; an HDR image needs nothing.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "core/colour.h"
#include "core/image.h"
#include "light/cubemap.h"
#include "scene_fixture.h"

namespace insitu {
namespace {

using namespace test;

// Six 16² grey shots; the ceiling's holds a clipped 4² lamp. A room box and the floor.
nlohmann::json clipped_shots_scene(SceneFixture& fx) {
  const char* keys[6] = {"+x", "-x", "up", "down", "+z", "-z"};
  nlohmann::json shots = {{"faced", "-z"}};
  for (int f = 0; f < 6; ++f) {
    Image shot(16, 16, 3, 0.4f);
    if (f == kPosY)
      for (int y = 6; y < 10; ++y)
        for (int x = 6; x < 10; ++x) shot.set_rgb(x, y, Rgb(1, 1, 1));
    const std::string name = std::string("shot") + std::to_string(f) + ".png";
    write_image(fx.dir.file(name), shot);
    shots[keys[f]] = name;
  }
  auto j = fx.scene;
  j["environment"] = {{"shots", shots},
                      {"exposure", 1.0},
                      {"room_box", {{"min", {-2, 0, -2}}, {"max", {2, 2.5, 2}}, {"capture", {0.5, 1, -0.5}}}}};
  j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  return j;
}

nlohmann::json light_of(const SceneFixture& fx, const std::string& report) {
  return nlohmann::json::parse(slurp(fx.dir.file(report)))["environment"]["light"];
}

TEST(LightRecovery, ClippedShotsAreFittedByDefaultAndReported) {
  SceneFixture fx;
  const std::string scene = fx.write(clipped_shots_scene(fx));
  const CliRun r = run_insitu(fx.dir, "render " + scene + " -o " + fx.dir.file("out.exr") + " --layers none");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto light = light_of(fx, "out.exr.report.json");
  ASSERT_TRUE(light.contains("inverse_lighting")) << light.dump();
  const auto& il = light["inverse_lighting"];
  EXPECT_EQ(il["sources"].size(), 1u);
  EXPECT_GT(il["pixels"].get<int>(), 0);
  // A random photo determines nothing for sure; whichever it is, the two fields agree.
  const bool determined = il["sources"][0]["determined"].get<bool>();
  EXPECT_EQ(light["determined_by"], determined ? "inverse lighting" : "lower bound");
  const CliRun c = run_insitu(fx.dir, "cubemap " + scene + " -o " + fx.dir.file("cube"));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_NE(c.out.find("light: "), std::string::npos) << c.out;
  EXPECT_NE(c.out.find("source toward"), std::string::npos) << c.out;
}

TEST(LightRecovery, OffLeavesTheLowerBound) {
  SceneFixture fx;
  auto j = clipped_shots_scene(fx);
  j["environment"]["inverse_lighting"] = false;
  const CliRun r = run_insitu(fx.dir, "render " + fx.write(j) + " -o " + fx.dir.file("out.exr") + " --layers none");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto light = light_of(fx, "out.exr.report.json");
  EXPECT_EQ(light["determined_by"], "lower bound");
  EXPECT_FALSE(light.contains("inverse_lighting"));
}

TEST(LightRecovery, AnHdrImageNeedsNothing) {
  SceneFixture fx;
  const CliRun r = run_insitu(fx.dir, "render " + fx.write() + " -o " + fx.dir.file("out.exr") + " --layers none");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(light_of(fx, "out.exr.report.json")["determined_by"], "hdr image");
}

// An 8-bit panorama is one single shot: its clipped lamp is fitted, and the report says it is a
// panorama, how much of the sphere it saw and how much clipped (the 16 × 4 lamp of 64 × 32).
TEST(LightRecovery, APanoramasClippedLightIsFittedAndReported) {
  SceneFixture fx;
  Image pano(64, 32, 3, 0.4f);
  for (int y = 2; y < 6; ++y)
    for (int x = 24; x < 40; ++x) pano.set_rgb(x, y, Rgb(1, 1, 1));
  write_image(fx.dir.file("pano.png"), pano);
  auto j = clipped_shots_scene(fx);
  j["environment"] = {{"image", "pano.png"},
                      {"yaw_deg", 90},
                      {"exposure", 1.0},
                      {"room_box", {{"min", {-2, 0, -2}}, {"max", {2, 2.5, 2}}, {"capture", {0.5, 1, -0.5}}}}};
  const CliRun r =
      run_insitu(fx.dir, "render " + fx.write(j) + " -o " + fx.dir.file("out.exr") + " --layers none --spp 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto env = nlohmann::json::parse(slurp(fx.dir.file("out.exr.report.json")))["environment"];
  EXPECT_NEAR(env["panorama"]["coverage_percent"].get<double>(), 100.0, 1e-6);
  EXPECT_NEAR(env["panorama"]["clipped_percent"].get<double>(), 100.0 * 64 / (64 * 32), 1e-6);
  EXPECT_EQ(env["panorama"]["yaw_deg"], 90);
  ASSERT_TRUE(env["light"].contains("inverse_lighting")) << env["light"].dump();
  EXPECT_EQ(env["light"]["inverse_lighting"]["sources"].size(), 1u);
  EXPECT_NE(env["light"]["determined_by"], "hdr image");
}

// Shots balanced bluer than a grey photo: the light is balanced back to it, said as a warning and
// in the report (blue's gain 0.4/0.3 of red's and green's, at luminance 1); "none" keeps theirs.
TEST(LightRecovery, TheLightIsWhiteBalancedToThePhoto) {
  SceneFixture fx;
  write_image(fx.dir.file("photo.png"), Image(fx.width, fx.height, 3, 0.5f));
  auto j = clipped_shots_scene(fx);
  const char* keys[6] = {"+x", "-x", "up", "down", "+z", "-z"};
  for (int f = 0; f < 6; ++f) {
    Image shot(16, 16, 3);
    for (int p = 0; p < 16 * 16; ++p) shot.set_rgb(p % 16, p / 16, Rgb(0.3f, 0.3f, 0.4f));
    write_image(fx.dir.file(std::string("blue") + keys[f] + ".png"), shot);
    j["environment"]["shots"][keys[f]] = std::string("blue") + keys[f] + ".png";
  }
  const CliRun r = run_insitu(fx.dir, "render " + fx.write(j) + " -o " + fx.dir.file("out.exr") + " --layers none");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("white balance differs from the photo's"), std::string::npos) << r.err;
  const auto wb = nlohmann::json::parse(slurp(fx.dir.file("out.exr.report.json")))["environment"]["white_balance"];
  ASSERT_TRUE(wb["determined"].get<bool>()) << wb.dump();
  // 0.3 and 0.4 as 8-bit codes, sRGB-decoded: the gain undoes their ratio.
  const double ratio = srgb_to_linear(std::round(0.4f * 255) / 255) / srgb_to_linear(std::round(0.3f * 255) / 255);
  EXPECT_NEAR(wb["gain"][0].get<double>() / wb["gain"][2].get<double>(), ratio, 0.01 * ratio);
  EXPECT_NEAR(wb["gain"][0].get<double>(), wb["gain"][1].get<double>(), 1e-3);
  j["environment"]["white_balance"] = "none";
  const CliRun off = run_insitu(fx.dir, "render " + fx.write(j) + " -o " + fx.dir.file("off.exr") + " --layers none");
  ASSERT_EQ(off.exit_code, 0) << off.err;
  EXPECT_TRUE(
      nlohmann::json::parse(slurp(fx.dir.file("off.exr.report.json")))["environment"]["white_balance"].is_null());
}

// A white sheet drawn in the photo: the report counts its pixels (sampled, clipped, used), and
// what determined the light is whatever the fit found, with a reference when the sheet served.
TEST(LightRecovery, AReferenceInThePhotoIsCountedInTheReport) {
  SceneFixture fx;
  auto j = clipped_shots_scene(fx);
  j["references"] = {{{"polygon_px", {{10, 20}, {30, 20}, {30, 31}, {10, 31}}}, {"albedo", 0.8}}};
  const CliRun r = run_insitu(fx.dir, "render " + fx.write(j) + " -o " + fx.dir.file("out.exr") + " --layers none");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto light = light_of(fx, "out.exr.report.json");
  const auto& refs = light["inverse_lighting"]["references"];
  ASSERT_EQ(refs.size(), 1u) << light.dump();
  EXPECT_EQ(refs[0]["albedo"], 0.8);
  EXPECT_GT(refs[0]["pixels_sampled"].get<int>(), 100);
  const int used = refs[0]["pixels_used"].get<int>();
  EXPECT_EQ(light["inverse_lighting"]["reference_surfaces"].get<int>(), used > 0 ? 1 : 0);
  if (light["inverse_lighting"]["sources"][0]["determined"].get<bool>()) {
    EXPECT_EQ(light["determined_by"], used > 0 ? "inverse lighting with a reference" : "inverse lighting");
  }
}

// A corner outside the photo is refused where it is; a reference where nothing clipped is warned
// of (it has no effect), not refused.
TEST(LightRecovery, AReferenceOutsideThePhotoIsRefusedAndOneNotNeededIsWarnedOf) {
  SceneFixture fx;
  auto j = clipped_shots_scene(fx);
  j["references"] = {{{"polygon_px", {{10, 20}, {48.5, 20}, {30, 31}}}, {"albedo", 0.8}}};
  const CliRun bad = run_insitu(fx.dir, "render " + fx.write(j) + " -o " + fx.dir.file("out.exr") + " --layers none");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("$.references[0].polygon_px[1]: (48.5, 20) lies outside the photo (48 x 32 pixels)"),
            std::string::npos)
      << bad.err;
  auto hdr = fx.scene;
  hdr["references"] = {{{"polygon_px", {{10, 20}, {30, 20}, {30, 31}}}, {"albedo", 0.18}}};
  const CliRun ok = run_insitu(fx.dir, "render " + fx.write(hdr) + " -o " + fx.dir.file("out.exr") + " --layers none");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.err.find("$.references[0]: nothing clipped in the environment and no opening in the room box: the "
                        "reference is not needed"),
            std::string::npos)
      << ok.err;
  // With an opening, a sheet helps fit the light through it (unseen_outside.h): no warning; a ball
  // does not take part there, and is warned of.
  hdr["environment"] = {{"image", "env.exr"}};
  hdr["environment"]["room_box"] = {{"min", {-2, 0, -2}},
                                    {"max", {2, 2.5, 2}},
                                    {"capture", {0.5, 1, -0.5}},
                                    {"openings", {{{"min", {-2, 0.8, -1}}, {"max", {-2, 2, 1}}}}}};
  hdr["references"].push_back({{"sphere", {{"center", {0, 0.3, 0}}, {"radius", 0.2}}}, {"albedo", 0.5}});
  const CliRun open =
      run_insitu(fx.dir, "render " + fx.write(hdr) + " -o " + fx.dir.file("open.exr") + " --layers none");
  ASSERT_EQ(open.exit_code, 0) << open.err;
  EXPECT_EQ(open.err.find("$.references[0]"), std::string::npos) << open.err;
  EXPECT_NE(open.err.find("$.references[1]: nothing clipped in the environment: a reference ball is not needed"),
            std::string::npos)
      << open.err;
}

// A reference plate (the reference photographed apart, so the photo stays clean) is read as the
// photo is; one of another size is refused where it is named, and nothing is written.
TEST(LightRecovery, AReferencePlateIsReadAndOneOfAnotherSizeIsRefused) {
  SceneFixture fx;
  auto j = clipped_shots_scene(fx);
  fs::copy_file(fx.dir.file("photo.png"), fx.dir.file("plate.png"));
  j["references"] = {
      {{"sphere", {{"center", {0.5, 0.2, -0.5}}, {"radius", 0.2}}}, {"albedo", 0.18}, {"photo", "plate.png"}}};
  const CliRun ok = run_insitu(fx.dir, "render " + fx.write(j) + " -o " + fx.dir.file("out.exr") + " --layers none");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const auto light = light_of(fx, "out.exr.report.json");
  const auto& refs = light["inverse_lighting"]["references"];
  ASSERT_EQ(refs.size(), 1u) << light.dump();
  EXPECT_EQ(refs[0]["kind"], "ball");
  write_image(fx.dir.file("small.png"), Image(24, 16, 3));
  j["references"][0]["photo"] = "small.png";
  const CliRun bad = run_insitu(fx.dir, "render " + fx.write(j) + " -o " + fx.dir.file("bad.exr") + " --layers none");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("$.references[0].photo: "), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("24 x 16 pixels, the photo 48 x 32: a plate is the photo's view"), std::string::npos)
      << bad.err;
  EXPECT_FALSE(fs::exists(fx.dir.file("bad.exr")));
}

}  // namespace
}  // namespace insitu
