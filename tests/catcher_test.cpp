#include <gtest/gtest.h>

#include "output/composite.h"
#include "integrators/registry.h"
#include "render/mesh.h"
#include "scene/pipeline.h"
#include "scene/scene_file.h"
#include "scene_fixture.h"
#include "test_util.h"

namespace insitu {
namespace {

// E/L = ∫ cos θ dω over the square [−half, half]² at height h, by the midpoint rule: ∫∫ h²/r⁴ dx dz
// (r² = x² + z² + h²); over the +Y face at distance 1, the same with h = 1 on [−1, 1]². A function,
// not a lambda: a C++17 lambda is implicitly constexpr, and g++ evaluated its 640 000 steps at
// compile time, 45 s of the file's 68 s.
double cosine_over_square(double half, double h) {
  const int q = 800;
  double sum = 0;
  for (int i = 0; i < q; ++i)
    for (int k = 0; k < q; ++k) {
      const double x = -half + (i + 0.5) * 2 * half / q, z = -half + (k + 0.5) * 2 * half / q;
      const double r2 = x * x + z * z + h * h;
      sum += h * h / (r2 * r2);
    }
  return sum * (2 * half / q) * (2 * half / q);
}

// A black square occluder [−a, a]² at height h above the catcher y = 0, under an environment
// whose only light is the +Y face (radiance L). At the point below the occluder's centre
//   E_total   = L · 2√2 atan(1/√2)                      (the face seen from its axis, Howell)
//   E_blocked = L · 4 · ½ · 2 · A/√(1+A²) · atan(A/√(1+A²)),  A = a/h  (the square, same formula)
// so the shadow ratio is 1 − E_blocked/E_total (0.5679 for A = ½). A black occluder sends no
// light back, so W/N is exactly that ratio in expectation. A sheer one of opacity a (MTL `d`, a
// glTF BLEND) blocks a of what it covers: 1 − a E_blocked/E_total, its shadow rays attenuated and
// its traced rays passing with probability 1 − a.
void expect_analytic_square_shadow(const std::string& mtl, double opacity) {
  test::TempDir dir;
  dir.write("q.mtl", mtl);
  const std::string obj =
      "mtllib q.mtl\nusemtl black\nv -0.5 1 -0.5\nv 0.5 1 -0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\nf 1 2 3 4\n";
  Warnings w;
  std::vector<Mesh> meshes;
  meshes.push_back(load_obj(dir.write("q.obj", obj), w));
  const EmbreeScene scene(std::move(meshes));
  const int n = 16;
  CubeMap env(n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) env.set_texel(kPosY, i, j, Rgb(2, 2, 2));
  env.update_borders();
  RenderInputs in;
  in.objects = &scene;
  in.environment = &env;
  CatcherPlane floor;
  floor.point = Vec3f::Zero();
  floor.normal = Vec3f(0, 1, 0);
  floor.albedo_from_photo = false;
  floor.albedo = Rgb(0.5f, 0.5f, 0.5f);
  floor.irradiance = irradiance_reference(env, {0, 1, 0});
  in.planes.push_back(floor);
  const auto path = make_integrator("path", in);
  // A camera ray that reaches (0, 0, 0) under the occluder.
  const Ray ray{{3.0f, 0.5f, 0.0f}, Vec3f(-3.0f, -0.5f, 0.0f).normalized()};
  double with = 0, without = 0, with2 = 0;
  const int count = 200000;
  for (int k = 0; k < count; ++k) {
    Sampler s(9, 0, std::uint64_t(k));
    const CameraSample cs = path->sample(ray, s);
    ASSERT_EQ(cs.coverage, 0.0f);
    with += cs.with_objects[0];
    with2 += double(cs.with_objects[0]) * cs.with_objects[0];
    without += cs.without_objects[0];
  }
  const double A = 0.5, s = A / std::sqrt(1 + A * A);
  const double E_total = 2 * std::sqrt(2.0) * std::atan(1 / std::sqrt(2.0)) * 2.0;
  const double E_blocked = 4 * 0.5 * 2 * s * std::atan(s) * 2.0;
  const double expected_ratio = 1 - opacity * E_blocked / E_total;
  // The closed forms against a midpoint quadrature of the same integrals (cosine_over_square).
  EXPECT_NEAR(E_blocked / E_total, cosine_over_square(0.5, 1.0) / cosine_over_square(1.0, 1.0), 1e-5);
  // The unoccluded estimate is the exact L = ρ/π·E_total on average; the ratio of means carries
  // the standard error of `with`.
  const double mean_with = with / count, se_with = std::sqrt((with2 / count - mean_with * mean_with) / count);
  const double exact_without = 0.5 / kPi * E_total;
  EXPECT_NEAR(without / count, exact_without, 0.01 * exact_without);
  EXPECT_NEAR(mean_with / exact_without, expected_ratio, 4 * se_with / exact_without + 0.005) << opacity;
}

TEST(Catcher, ShadowRatioOfASquareOccluderIsTheAnalyticFormFactor) {
  expect_analytic_square_shadow("newmtl black\nKd 0 0 0\n", 1.0);
}

TEST(Catcher, ASheerSquaresShadowIsItsOpacityOfTheOpaqueOnes) {
  expect_analytic_square_shadow("newmtl black\nKd 0 0 0\nd 0.4\n", 0.4);
}

// With a catcher plane, no objects (or objects out of view) leave the photo bit for bit, and the
// ratio and additive composites agree where the albedo comes from the photo.
TEST(Catcher, DifferentialLeavesUntouchedPixelsAndModesAgree) {
  test::SceneFixture fx;
  auto j = fx.scene;
  j["render"] = {{"integrator", "path"}, {"spp", 4}};
  j["local_scene"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  j["objects"] = nlohmann::json::array();
  j["output"] = {{"image", "out/c.png"}};
  for (int variant = 0; variant < 2; ++variant) {
    if (variant == 1) j["objects"] = {{{"mesh", "good_quad.obj"}, {"translate", {0, 0, 50}}}};
    const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
    const RenderResult r = render_scene(s);
    write_outputs(s, r);
    EXPECT_EQ(read_image_file(fx.dir.file("out/c.png")).stored.data,
              read_image_file(fx.dir.file("photo.png")).stored.data)
        << "variant " << variant;
  }
  // A quad floating above the floor in view: the modes agree in expectation; with the albedo
  // from the photo and E exact, additive = P + P/E·(Ê_with − Ê_without), ratio = P·Ê_with/Ê_without.
  j["objects"] = {{{"mesh", "good_quad.obj"}, {"translate", {0, 0.3, 0}}}};
  j["render"]["spp"] = 64;
  SceneSpec spec = parse_scene_file(fx.write(j));
  const LoadedScene s = load_scene(spec);
  const RenderResult r = render_scene(s);
  const Image additive = composite(s.photo_linear, r.layers, CompositeMode::kAdditive);
  const Image ratio = composite(s.photo_linear, r.layers, CompositeMode::kRatio);
  double diff = 0, total = 0;
  for (std::size_t i = 0; i < ratio.data.size(); ++i) {
    diff += std::abs(additive.data[i] - ratio.data[i]);
    total += ratio.data[i];
  }
  EXPECT_LT(diff / total, 0.02);
}

struct WallScene {
  test::TempDir dir;
  std::unique_ptr<EmbreeScene> scene;
  CubeMap env{8};
  RenderInputs in;
  explicit WallScene(double scale) {
    // A black box x in [0, 100], y in [0, 100] (resting exactly on the floor), z in [−100, 100],
    // all scaled: a vertical half-space wall at x = 0.
    dir.write("w.mtl", "newmtl black\nKd 0 0 0\n");
    const std::string obj =
        "mtllib w.mtl\nusemtl black\n"
        "v 0 0 -100\nv 100 0 -100\nv 100 100 -100\nv 0 100 -100\nv 0 0 100\nv 100 0 100\nv 100 100 100\nv 0 100 100\n"
        "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";
    Warnings w;
    std::vector<Mesh> meshes;
    meshes.push_back(load_obj(dir.write("w.obj", obj), w));
    transform_mesh(meshes.back(), object_transform({0, 0, 0}, 0, {0, 1, 0}, Vec3d::Constant(scale)));
    scene = std::make_unique<EmbreeScene>(std::move(meshes));
    for (int f = 0; f < 6; ++f)
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) env.set_texel(f, i, j, Rgb(1, 1, 1));
    env.update_borders();
    in.objects = scene.get();
    in.environment = &env;
    CatcherPlane floor;
    floor.point = Vec3f::Zero();
    floor.normal = Vec3f(0, 1, 0);
    floor.albedo_from_photo = false;
    floor.albedo = Rgb(0.5f, 0.5f, 0.5f);
    floor.irradiance = irradiance_reference(env, {0, 1, 0});
    in.planes.push_back(floor);
  }
};

// An object face coincident with the floor: right beside a wall resting on it, a uniform sky is
// exactly half blocked (the wall's plane halves the cosine-weighted hemisphere), so W/N = ½ — no
// light leaks under the wall and no acne darkens it further — at 1 mm and 1 km scale alike.
TEST(Catcher, WallRestingOnTheFloorBlocksExactlyHalf) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    WallScene w(scale);
    const auto path = make_integrator("path", w.in);
    const Vec3f x(float(-1e-4 * scale), 0, 0);
    const Vec3f eye = x + Vec3f(-2, 1, 0.3f) * float(scale);
    const Ray ray{eye, (x - eye).normalized()};
    double with = 0, without = 0, with2 = 0;
    const int count = 100000;
    for (int k = 0; k < count; ++k) {
      Sampler s(4, 0, std::uint64_t(k));
      const CameraSample cs = path->sample(ray, s);
      ASSERT_TRUE(cs.with_objects.allFinite());
      ASSERT_GE(cs.with_objects[0], 0.0f);
      with += cs.with_objects[0];
      with2 += double(cs.with_objects[0]) * cs.with_objects[0];
      without += cs.without_objects[0];
    }
    const double exact_without = 0.5 / kPi * kPi * 1.0;  // ρ/π · E, E = π·L
    const double m = with / count, se = std::sqrt((with2 / count - m * m) / count);
    EXPECT_NEAR(without / count, exact_without, 0.01 * exact_without) << scale;
    EXPECT_NEAR(m / exact_without, 0.5, 4 * se / exact_without + 0.002) << "scale " << scale;
  }
}

// Grazing camera rays along the floor (down to 1e−6 rad below the horizon) meet it far away and
// give finite, positive estimates.
TEST(Catcher, GrazingRaysAlongTheFloor) {
  WallScene w(1.0);
  const auto path = make_integrator("path", w.in);
  for (float slope : {1e-6f, 1e-4f, 1e-2f}) {
    const Ray ray{Vec3f(-1, 0.01f, 0), Vec3f(-1, -slope, 0.2f).normalized()};
    Sampler s(1, 0, 0);
    const CameraSample cs = path->sample(ray, s);
    EXPECT_TRUE(cs.with_objects.allFinite()) << slope;
    EXPECT_TRUE(cs.without_objects.allFinite()) << slope;
    EXPECT_GT(cs.without_objects[0], 0.0f) << slope;
  }
}

// Parallax correction: with a room box, a floor point near the bright +X wall receives more of
// its light than a point across the room; without it, both receive the same.
TEST(Catcher, RoomBoxParallaxFavoursThePointNearTheWindow) {
  CubeMap env(8);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) env.set_texel(f, i, j, Rgb::Constant(f == kPosX ? 10.0f : 1.0f));
  env.update_borders();
  const EmbreeScene empty({});
  auto irradiance_at = [&](bool box, float x) {
    RenderInputs in;
    in.objects = &empty;
    in.environment = &env;
    if (box) in.room = RoomBox{Vec3f(-5, 0, -5), Vec3f(5, 3, 5), Vec3f(0, 1.5f, 0), {}, std::nullopt};
    CatcherPlane floor;
    floor.point = Vec3f::Zero();
    floor.normal = Vec3f(0, 1, 0);
    floor.albedo_from_photo = false;
    floor.albedo = Rgb::Constant(kPiF);  // ρ/π = 1: the estimates are irradiance
    in.planes.push_back(floor);
    const auto path = make_integrator("path", in);
    const Ray ray{Vec3f(x, 1, 0.5f), Vec3f(0, -1, -0.5f).normalized()};
    double sum = 0;
    const int count = 40000;
    for (int k = 0; k < count; ++k) {
      Sampler s(3, 0, std::uint64_t(k));
      sum += path->sample(ray, s).without_objects[0];
    }
    return sum / count;
  };
  const double near = irradiance_at(true, 4.5f), far = irradiance_at(true, -4.5f);
  EXPECT_GT(near, 1.5 * far);
  const double near0 = irradiance_at(false, 4.5f), far0 = irradiance_at(false, -4.5f);
  EXPECT_NEAR(near0 / far0, 1.0, 0.05);
}

// The same occluder over a floor given as a catcher mesh (a 200 m quad) instead of a plane: the
// same analytic shadow ratio.
TEST(Catcher, MeshCatcherGivesTheSameShadowAsAPlane) {
  test::TempDir dir;
  dir.write("q.mtl", "newmtl black\nKd 0 0 0\n");
  Warnings w;
  std::vector<Mesh> occluder, floor;
  occluder.push_back(load_obj(
      dir.write("q.obj",
                "mtllib q.mtl\nusemtl black\nv -0.5 1 -0.5\nv 0.5 1 -0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\nf 1 2 3 4\n"),
      w));
  floor.push_back(
      load_obj(dir.write("f.obj", "v -100 0 -100\nv 100 0 -100\nv 100 0 100\nv -100 0 100\nf 1 4 3 2\n"), w));
  const EmbreeScene objects(std::move(occluder)), catchers(std::move(floor));
  const int n = 16;
  CubeMap env(n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) env.set_texel(kPosY, i, j, Rgb(2, 2, 2));
  env.update_borders();
  const auto field = make_irradiance(IrradianceMode::kExact, env);
  RenderInputs in;
  in.objects = &objects;
  in.environment = &env;
  in.catcher_meshes = &catchers;
  in.catcher_mesh_info.push_back({false, Rgb(0.5f, 0.5f, 0.5f)});
  in.catcher_irradiance = field.get();
  const auto path = make_integrator("path", in);
  const Ray ray{{3.0f, 0.5f, 0.0f}, Vec3f(-3.0f, -0.5f, 0.0f).normalized()};
  double with = 0, with2 = 0, without = 0;
  const int count = 200000;
  for (int k = 0; k < count; ++k) {
    Sampler s(9, 0, std::uint64_t(k));
    const CameraSample cs = path->sample(ray, s);
    with += cs.with_objects[0];
    with2 += double(cs.with_objects[0]) * cs.with_objects[0];
    without += cs.without_objects[0];
  }
  const double s = 0.5 / std::sqrt(1.25);
  const double E_total = 2 * std::sqrt(2.0) * std::atan(1 / std::sqrt(2.0)) * 2.0;
  const double expected_ratio = 1 - 4 * 0.5 * 2 * s * std::atan(s) * 2.0 / E_total;
  const double exact_without = 0.5 / kPi * E_total;
  const double m = with / count, se = std::sqrt((with2 / count - m * m) / count);
  EXPECT_NEAR(without / count, exact_without, 0.01 * exact_without);
  EXPECT_NEAR(m / exact_without, expected_ratio, 4 * se / exact_without + 0.005);
}

TEST(Catcher, LocalSceneMeshInTheSceneFile) {
  test::SceneFixture fx;
  auto j = fx.scene;
  j["render"] = {{"integrator", "path"}, {"spp", 4}};
  j["local_scene"] = {
      {{"mesh", "good_quad.obj"}, {"scale", 4}, {"translate", {-1, 0, 1}}, {"albedo", {0.4, 0.4, 0.4}}}};
  j["objects"] = {{{"mesh", "good_quad.obj"}, {"translate", {0, 0.3, 0}}}};
  const LoadedScene s = load_scene(parse_scene_file(fx.write(j)));
  EXPECT_EQ(s.catcher_meshes->meshes().size(), 1u);
  const RenderResult r = render_scene(s);
  const Image touched = touched_mask(r.layers);
  double changed = 0;
  for (float v : touched.data) changed += v;
  EXPECT_GT(changed, 0);
  j["local_scene"] = {{{"mesh", "good_quad.obj"}, {"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  EXPECT_THROW(parse_scene_file(fx.write(j)), InputError);
}

}  // namespace
}  // namespace insitu
