// What determined the light, end to end (scene/light_recovery.h): a scene of six 8-bit shots, one
// with a clipped lamp, is fitted by default and says so in its report and in `insitu cubemap`;
// environment.inverse_lighting false leaves the lower bound; an HDR image needs nothing.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_util.h"
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

}  // namespace
}  // namespace insitu
