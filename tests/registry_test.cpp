// The integrators' registry (src/integrators/registry.h): parameters read by each integrator itself,
// and the invariants every registered integrator must keep, run over the whole table so that a
// new integrator is tested without new test code.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "cube_fixture.h"
#include "core/camera.h"
#include "light/irradiance.h"
#include "output/settings.h"
#include "integrators/registry.h"
#include "render/mesh.h"
#include "render/render.h"
#include "scene/pipeline.h"
#include "scene/scene_file.h"
#include "scene_fixture.h"
#include "box_fixture.h"
#include "test_util.h"

namespace insitu {
namespace {

using nlohmann::json;

ResolvedIntegrator resolve(const std::string& name, const json& render, Warnings* warnings = nullptr) {
  Warnings w;
  return resolve_integrator(name, {render, "scene.json", "$.render"}, warnings ? *warnings : w);
}

std::string error_of(const std::string& name, const json& render) {
  try {
    resolve(name, render);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Registry, DefaultsAreFilledIn) {
  EXPECT_EQ(resolve("realtime", json::object()).params, json::object());
  EXPECT_EQ(resolve("irradiance", json::object()).params, (json{{"irradiance", "exact"}}));
  EXPECT_EQ(resolve("path", json::object()).params, (json{{"max_depth", 5},
                                                          {"catcher_bounces", 5},
                                                          {"photo_bounces", 1},
                                                          {"toward_objects", 0.5},
                                                          {"change_grid", 64}}));
}

TEST(Registry, FlatOrInTheIntegratorsOwnObject) {
  const json path_3 = {
      {"max_depth", 3}, {"catcher_bounces", 5}, {"photo_bounces", 1}, {"toward_objects", 0.5}, {"change_grid", 64}};
  EXPECT_EQ(resolve("path", {{"max_depth", 3}}).params, path_3);
  EXPECT_EQ(resolve("path", {{"path", {{"max_depth", 3}}}}).params, path_3);
  // DESIGN.md's render.irradiance is the irradiance integrator's flat parameter; its object is too.
  EXPECT_EQ(resolve("irradiance", {{"irradiance", "sh9"}}).params, (json{{"irradiance", "sh9"}}));
  EXPECT_EQ(resolve("irradiance", {{"irradiance", {{"irradiance", "gaussian"}}}}).params,
            (json{{"irradiance", "gaussian"}}));
}

TEST(Registry, ErrorsNameTheKey) {
  EXPECT_EQ(error_of("path", {{"max_depth", 3}, {"path", {{"max_depth", 4}}}}),
            "scene.json:$.render.max_depth: given twice: here and in render.path (give it once)");
  EXPECT_EQ(error_of("path", {{"path", {{"max_dept", 4}}}}),
            "scene.json:$.render.path.max_dept: unknown key (the path integrator reads: catcher_bounces, change_grid, "
            "max_depth, photo_bounces, toward_objects)");
  EXPECT_NE(error_of("path", {{"max_dept", 4}}).find("scene.json:$.render.max_dept: unknown key (expected one of: "),
            std::string::npos);
  // "irradiance" is a key twice over, once in each role (issue 46: the list named it twice, as if
  // by mistake): the integrators' objects are listed apart, from the registry.
  std::string blocks;
  for (const auto& e : integrator_registry()) blocks += std::string(blocks.empty() ? "" : ", ") + e.name;
  EXPECT_NE(error_of("path", {{"max_dept", 4}}).find("; or an integrator's object of parameters: " + blocks + ")"),
            std::string::npos)
      << error_of("path", {{"max_dept", 4}});
  EXPECT_EQ(error_of("path", {{"max_depth", 0}}), "scene.json:$.render.max_depth: 0 is out of range [1, 1000]");
  EXPECT_EQ(error_of("path", {{"irradiance", "best"}}),
            "scene.json:$.render.irradiance: expected \"gaussian\", \"sh9\", \"exact\" or \"volume\"");
  EXPECT_EQ(error_of("raytrace", json::object()),
            "scene.json:$.render.integrator: unknown integrator 'raytrace' (known: realtime, irradiance, path)");
  // Another integrator's unknown key is refused too: a typo never waits for the day it is used.
  EXPECT_NE(error_of("realtime", {{"path", {{"depth", 4}}}}).find("$.render.path.depth: unknown key"),
            std::string::npos);
}

TEST(Registry, AnotherIntegratorsParametersAreWarnedOf) {
  Warnings w;
  resolve("realtime", {{"max_depth", 3}, {"irradiance", {{"irradiance", "sh9"}}}}, &w);
  ASSERT_EQ(w.items.size(), 2u);
  EXPECT_EQ(w.items[0], "render.irradiance: has no effect: the realtime integrator is used");
  EXPECT_EQ(w.items[1], "render.max_depth: has no effect: the realtime integrator does not read it (only path does)");
  Warnings none;
  resolve("path", {{"integrator", "path"}, {"spp", 4}, {"seed", 2}, {"max_depth", 3}}, &none);
  EXPECT_TRUE(none.items.empty());
}

// ---- The docs and scripts against the tables ---------------------------------------------------

std::string read_source(const std::string& rel) {
  std::ifstream in(test::source_dir() + "/" + rel);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// `insitu tradeoff` asks the registry for its roles, not for names: one reference, the only
// integrator that is Monte Carlo and catches shadows in a room box, and one legacy integrator.
TEST(Registry, TheTradeoffsRolesAreCapabilitiesHeldOnceEach) {
  int references = 0, legacies = 0;
  for (const auto& e : integrator_registry()) references += e.uses.reference, legacies += e.uses.legacy;
  EXPECT_EQ(references, 1);
  EXPECT_EQ(legacies, 1);
  const IntegratorCapabilities& r = reference_integrator().uses;
  EXPECT_TRUE(r.monte_carlo && r.local_scene && r.room_box);
  EXPECT_FALSE(legacy_integrator().uses.monte_carlo);
  EXPECT_STREQ(reference_integrator().name, "path");
  EXPECT_STREQ(legacy_integrator().name, "realtime");
}

// The directional irradiance modes are every mode of the table but the one that needs a room box.
TEST(Registry, DirectionalIrradianceModesAreTheTablesButVolume) {
  std::vector<std::string> expected;
  for (const auto& row : kIrradianceModes)
    if (row.value != IrradianceMode::kVolume) expected.push_back(row.name);
  std::vector<std::string> listed;
  for (IrradianceMode m : directional_irradiance_modes()) listed.push_back(irradiance_mode_name(m));
  EXPECT_EQ(listed, expected);
}

// scripts/bit-identity.sh renders every integrator, irradiance mode and tone map.
TEST(Registry, BitIdentityScriptCoversEveryTable) {
  const std::string script = read_source("scripts/bit-identity.sh");
  ASSERT_FALSE(script.empty());
  for (const auto& e : integrator_registry()) EXPECT_NE(script.find(e.name), std::string::npos) << e.name;
  for (const auto& name : names_of(kIrradianceModes)) EXPECT_NE(script.find(name), std::string::npos) << name;
  for (const auto& name : names_of(kToneMaps)) EXPECT_NE(script.find(name), std::string::npos) << name;
}

// ---- The invariants of every registered integrator -------------------------------------------

class EveryIntegrator : public ::testing::TestWithParam<std::string> {};

std::vector<std::string> registered_names() {
  std::vector<std::string> names;
  for (const auto& e : integrator_registry()) names.emplace_back(e.name);
  return names;
}

// Furnace: a convex Lambertian object of albedo ρ in a constant environment L has radiance ρ·L
// everywhere, whatever the integrator (the blur of a constant is that constant; E = πL; a convex
// object neither shadows nor lights itself) — within 4 standard errors of the mean over the
// samples, plus 1e-3 relative for the float arithmetic of the blur and the irradiance cube.
TEST_P(EveryIntegrator, FurnaceConvexObjectReflectsAlbedoTimesRadiance) {
  test::TempDir dir;
  const CubeMap env = test::constant_cube(8, Rgb::Constant(0.5f));
  const EmbreeScene box = test::make_box(dir, "0.8 0.6 0.4", 1.0);
  RenderInputs in;
  in.objects = &box;
  in.environment = &env;
  const auto integrator = make_integrator(GetParam(), in);
  const Ray rays[] = {{Vec3f(0.3f, 0.2f, 5), Vec3f(-0.05f, 0.02f, -1).normalized()},
                      {Vec3f(3, 4, 2), -Vec3f(3, 4, 2).normalized()}};
  const Rgb expected = Rgb(0.8f, 0.6f, 0.4f) * 0.5f;
  for (std::size_t r = 0; r < 2; ++r) {
    Eigen::Array3d sum = Eigen::Array3d::Zero(), sum2 = Eigen::Array3d::Zero();
    const int n = 2000;
    for (int k = 0; k < n; ++k) {
      Sampler s(7, r, std::uint64_t(k));
      const CameraSample cs = integrator->sample(rays[r], s);
      ASSERT_EQ(cs.coverage, 1.0f);
      const Eigen::Array3d x = cs.radiance.cast<double>();
      sum += x;
      sum2 += x * x;
    }
    const Eigen::Array3d mean = sum / n, se = ((sum2 / n - mean * mean).max(0.0) / n).sqrt();
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(mean[c], expected[c], 4 * se[c] + 1e-3 * expected[c]) << "ray " << r << " channel " << c;
  }
}

// No objects: the composite is the photo, bit for bit, with a local scene to catch shadows.
TEST_P(EveryIntegrator, EmptySceneReproducesThePhotoBitForBit) {
  test::SceneFixture fx;
  fx.scene["objects"] = json::array();
  fx.scene["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  fx.scene["render"] = {{"integrator", GetParam()}, {"spp", 4}};
  const LoadedScene scene = load_scene(parse_scene_file(fx.write()));
  const RenderResult r = render_scene(scene);
  ASSERT_EQ(r.composite_encoded.data.size(), scene.photo.stored.data.size());
  EXPECT_TRUE(r.composite_encoded.data == scene.photo.stored.data);
}

// Radiance from 1e-6 to 1e5 in one cube, objects of a millimetre and of a kilometre, rays at
// grazing angles: every layer finite and no sample zeroed as non-finite.
TEST_P(EveryIntegrator, FiniteAtTheExtremes) {
  test::TempDir dir;
  CubeMap env(8);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) env.set_texel(f, i, j, Rgb::Constant((i + j + f) % 2 ? 1e5f : 1e-6f));
  env.update_borders();
  for (double scale : {1e-3, 1e3}) {
    const EmbreeScene box = test::make_box(dir, "0.9 0.5 0.1", scale);
    RenderInputs in;
    in.objects = &box;
    in.environment = &env;
    const Vec3d eye = Vec3d(4, 0.001, 3) * scale;  // nearly in the plane of the box's top face
    const Camera cam = Camera::look_at(eye, Vec3d(0, 1, 0) * scale, Vec3d(0, 1, 0), 40, 16, 12);
    in.camera = &cam;
    const auto integrator = make_integrator(GetParam(), in);
    const RenderLayers layers = render(cam, *integrator, {4, 1});
    EXPECT_EQ(layers.nonfinite_samples, 0u) << "scale " << scale;
    for (const Image* img : {&layers.objects, &layers.alpha, &layers.with_objects, &layers.without_objects,
                             &layers.normal, &layers.albedo, &layers.depth, &layers.variance})
      for (float v : img->data) ASSERT_TRUE(std::isfinite(v)) << "scale " << scale;
    float covered = 0;
    for (float a : layers.alpha.data) covered += a;
    EXPECT_GT(covered, 0) << "the box is in view at scale " << scale;
  }
}

INSTANTIATE_TEST_SUITE_P(Registry, EveryIntegrator, ::testing::ValuesIn(registered_names()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

}  // namespace
}  // namespace insitu
