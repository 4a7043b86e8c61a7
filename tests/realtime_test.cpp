#include <gtest/gtest.h>

#include <random>

#include "cube_fixture.h"
#include "light/gaussian_irradiance.h"
#include "integrators/registry.h"
#include "render/mesh.h"
#include "test_util.h"

namespace insitu {
namespace {

// A closed sphere of reflectance ρ in a constant environment L renders ρ·L everywhere it covers
// (the blur of a constant is that constant; the legacy path has no π).
TEST(Realtime, ConstantEnvironmentGivesBaseColourTimesRadiance) {
  test::TempDir dir;
  dir.write("s.mtl", "newmtl m\nKd 0.5 0.25 1\n");
  std::string obj = "mtllib s.mtl\nusemtl m\n";
  const int nu = 24, nv = 12;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const double th = kPi * j / nv, ph = 2 * kPi * i / nu;
      obj += "v " + std::to_string(std::sin(th) * std::cos(ph)) + " " + std::to_string(std::cos(th)) + " " +
             std::to_string(std::sin(th) * std::sin(ph)) + "\n";
    }
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int a = j * (nu + 1) + i + 1, b = a + nu + 1;
      obj += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(b + 1) + " " +
             std::to_string(b) + "\n";
    }
  Warnings w;
  std::vector<Mesh> meshes;
  meshes.push_back(load_obj(dir.write("s.obj", obj), w));
  const EmbreeScene scene(std::move(meshes));
  const CubeMap env = test::constant_cube(8, Rgb(2.0f, 3.0f, 1e4f));
  RenderInputs in;
  in.objects = &scene;
  in.environment = &env;
  const auto integrator = make_integrator("realtime", in);
  std::mt19937 rng(2);
  std::normal_distribution<float> g(0, 1);
  for (int k = 0; k < 500; ++k) {
    const Vec3f from = Vec3f(g(rng), g(rng), g(rng)).normalized() * 5.0f;
    const Vec3f target = Vec3f(g(rng), g(rng), g(rng)).normalized() * 0.8f * std::abs(g(rng)) / 3.0f;  // well inside
    Sampler s(1, std::uint64_t(k), 0);
    const CameraSample cs = integrator->sample({from, (target - from).normalized()}, s);
    ASSERT_EQ(cs.coverage, 1.0f);
    EXPECT_NEAR(cs.radiance[0], 1.0f, 1e-5f);
    EXPECT_NEAR(cs.radiance[1], 0.75f, 1e-5f);
    EXPECT_NEAR(cs.radiance[2], 1e4f, 1e-1f);
  }
}

}  // namespace
}  // namespace insitu
