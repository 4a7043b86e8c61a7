#include <gtest/gtest.h>

#include "cube_fixture.h"
#include "box_fixture.h"
#include "integrators/registry.h"
#include "light/equirect.h"
#include "light/irradiance.h"
#include "test_util.h"

namespace insitu {
namespace {

struct Estimate {
  Rgb mean, se;
};

Estimate estimate(const Integrator& integ, const Ray& ray, int samples, std::uint64_t pixel) {
  Eigen::Array3d sum = Eigen::Array3d::Zero(), sum2 = Eigen::Array3d::Zero();
  for (int k = 0; k < samples; ++k) {
    Sampler s(5, pixel, std::uint64_t(k));
    const CameraSample cs = integ.sample(ray, s);
    const Eigen::Array3d x = (cs.radiance * cs.coverage).cast<double>();
    sum += x;
    sum2 += x * x;
  }
  const Eigen::Array3d mean = sum / samples;
  return {mean.cast<float>(), ((sum2 / samples - mean * mean) / samples).sqrt().cast<float>()};
}

// White furnace: reflectance 1 in a constant environment L reflects exactly L, for `path` within
// its standard error, for `irradiance` exactly — at 1 mm, 1 m and 1 km.
TEST(Path, WhiteFurnaceAtEveryScale) {
  test::TempDir dir;
  const CubeMap env = test::constant_cube(8, Rgb(0.7f, 0.7f, 0.7f));
  for (double scale : {1e-3, 1.0, 1e3}) {
    const EmbreeScene box = test::make_box(dir, "1 1 1", scale);
    RenderInputs in;
    in.objects = &box;
    in.environment = &env;
    const auto path = make_integrator("path", in);
    // Inside a uniformly emitting room box (room_light.h), captured off-centre, with a window
    // and a door: the same (the room's mixture of wall and portal samples is unbiased). Its walls
    // are white (ρ = 1 from the photo): the objects' change would travel between them without
    // loss until max_depth cut it, so the change is followed over one real bounce here (the
    // further bounces have their own analytic test below, CatcherBounces…).
    const json one_bounce = {{"catcher_bounces", 1}};
    RenderInputs in_room = in;
    const float m = float(scale);
    in_room.room =
        RoomBox{Vec3f(-6, -6, -6) * m,
                Vec3f(6, 6, 7) * m,
                Vec3f(1.5f, 0.5f, -2) * m,
                {{0, Vec3f(-6, -1, -3) * m, Vec3f(-6, 3, 2) * m}, {2, Vec3f(1, -6, 7) * m, Vec3f(3, 0, 7) * m}},
                std::nullopt};
    const auto path_room = make_integrator("path", in_room, one_bounce);
    const auto irr = make_integrator("irradiance", in);
    const std::vector<Ray> rays = {{Vec3f(0.3f, 0.2f, 5) * float(scale), Vec3f(-0.05f, 0.02f, -1).normalized()},
                                   {Vec3f(3, 4, 2) * float(scale), -Vec3f(3, 4, 2).normalized()}};
    for (std::size_t r = 0; r < rays.size(); ++r) {
      const Estimate e = estimate(*path, rays[r], 4000, r);
      EXPECT_NEAR(e.mean[0], 0.7f, 4 * e.se[0] + 1e-6f) << "scale " << scale;
      const Estimate e_room = estimate(*path_room, rays[r], 4000, r);
      EXPECT_NEAR(e_room.mean[0], 0.7f, 4 * e_room.se[0] + 1e-6f) << "room box, scale " << scale;
      Sampler s(1, 0, 0);
      EXPECT_NEAR(irr->sample(rays[r], s).radiance[0], 0.7f, 1e-4f);
    }
  }
}

// For a convex object alone (nothing to occlude, no interreflection), `path` equals ρ/π times the
// exact irradiance at the normal (the brute-force reference), within its standard error.
TEST(Path, ConvexObjectEqualsExactIrradiance) {
  INSITU_REQUIRE_SHARED();
  test::TempDir dir;
  const CubeMap env = cube_from_equirect(linearize(read_image_file(test::shared_data() + "/hdri/sunset.exr")), 16);
  const EmbreeScene box = test::make_box(dir, "0.5 0.4 0.3", 1.0);
  RenderInputs in;
  in.objects = &box;
  in.environment = &env;
  const auto path = make_integrator("path", in);
  const struct {
    Ray ray;
    Vec3d normal;
  } cases[] = {
      {{Vec3f(0.2f, 0.1f, 5), Vec3f(0, 0, -1)}, {0, 0, 1}},
      {{Vec3f(0.1f, 5, -0.3f), Vec3f(0, -1, 0)}, {0, 1, 0}},
      {{Vec3f(-5, 0.2f, 0.4f), Vec3f(1, 0, 0)}, {-1, 0, 0}},
      {{Vec3f(0.3f, -5, 0.1f), Vec3f(0, 1, 0)}, {0, -1, 0}},
  };
  for (std::size_t c = 0; c < 4; ++c) {
    const Estimate e = estimate(*path, cases[c].ray, 20000, c);
    const Rgb expected = Rgb(0.5f, 0.4f, 0.3f) * irradiance_reference(env, cases[c].normal) / kPiF;
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(e.mean[k], expected[k], 4 * e.se[k] + 1e-5f * expected[k]) << "case " << c << " channel " << k;
  }
}

// A floor catcher plane through the origin, facing up, of the given albedo.
CatcherPlane floor_plane(float albedo) {
  CatcherPlane p;
  p.point = Vec3f::Zero();
  p.normal = Vec3f(0, 1, 0);
  p.albedo_from_photo = false;
  p.albedo = Rgb::Constant(albedo);
  return p;
}

// White furnace with the local scene: a white box standing on a white floor in a constant
// environment L. Every point of the upper half-space then sees L in every direction (sky, floor and
// box all return L), so the box reflects exactly L wherever it is seen — through any number of
// bounces between it and the real floor, which the objects' paths now shade rather than look up.
TEST(Path, WhiteFurnaceWithTheLocalScene) {
  test::TempDir dir;
  const CubeMap env = test::constant_cube(8, Rgb::Constant(0.7f));
  const EmbreeScene box = test::make_box(dir, "1 1 1", 1.0, Vec3d(0, 1.001, 0));
  RenderInputs in;
  in.objects = &box;
  in.environment = &env;
  in.planes = {floor_plane(1.0f)};
  const auto path = make_integrator("path", in, {{"max_depth", 1000}});
  // The side of the box 2 cm above the floor, and its top.
  const Ray rays[] = {{Vec3f(5, 0.021f, 0.3f), Vec3f(-1, 0, 0)}, {Vec3f(0.2f, 6, 0.1f), Vec3f(0, -1, 0)}};
  for (std::size_t r = 0; r < 2; ++r) {
    const Estimate e = estimate(*path, rays[r], 8000, r);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(e.mean[c], 0.7f, 4 * e.se[c] + 1e-5f) << "ray " << r;
  }
}

// Objects see their own shadows: the underside of a 2 m box hovering 1 cm above the floor sees the
// floor in the box's own shadow, lit only through the 1 cm gap, so it is nearly black. Looked up
// in the photo (which has no shadow of the box) the floor would give it ρ_box · L_floor = 0.8 · 0.5
// in this constant sky L = 1 over a floor of albedo 0.5. The camera looks up from below the floor
// (planes catch from their front only).
TEST(Path, ObjectsSeeTheirOwnShadowsOnTheLocalScene) {
  test::TempDir dir;
  const CubeMap env = test::constant_cube(8, Rgb::Constant(1.0f));
  const EmbreeScene box = test::make_box(dir, "0.8 0.8 0.8", 1.0, Vec3d(0, 1.01, 0));
  RenderInputs in;
  in.objects = &box;
  in.environment = &env;
  in.planes = {floor_plane(0.5f)};
  const auto path = make_integrator("path", in);
  const Estimate e = estimate(*path, {Vec3f(0.1f, -1, 0.05f), Vec3f(0, 1, 0)}, 4000, 0);
  const float unshadowed = 0.8f * 0.5f;
  EXPECT_LT(e.mean[0], 0.05f * unshadowed) << "se " << e.se[0];
  EXPECT_GT(e.mean[0], 0.0f);  // some light leaks in through the gap
}

// Walls that catch (issue 12): in a constant room of radiance 1, a wall point beside a 2 m box
// standing 10 cm from the +x wall loses much of the room's light to the box (with < without),
// while the −x wall across the room barely changes. Without objects the wall reflects what the
// room shows there: ρ from the photo (here the room light itself, 1) and the wall's irradiance.
TEST(Path, WallsOfTheRoomBoxCatchShadows) {
  test::TempDir dir;
  const CubeMap env = test::constant_cube(8, Rgb::Constant(1.0f));
  const EmbreeScene box = test::make_box(dir, "0.5 0.5 0.5", 1.0, Vec3d(3.9, 1.5, 0));
  RenderInputs in;
  in.objects = &box;
  in.environment = &env;
  in.room = RoomBox{Vec3f(-5, 0, -5), Vec3f(5, 3, 5), Vec3f(0, 1.5f, 0), {}, std::nullopt};
  // The walls' own change, one real bounce: white walls (ρ = 1) would pass the box's shadow on
  // round the room without loss (CatcherBounces… below).
  const auto path = make_integrator("path", in, {{"catcher_bounces", 1}});
  auto walls = [&](const Ray& ray) {
    Eigen::Array2d sum = Eigen::Array2d::Zero();
    const int count = 4000;
    for (int k = 0; k < count; ++k) {
      Sampler s(9, 0, std::uint64_t(k));
      const CameraSample cs = path->sample(ray, s);
      EXPECT_EQ(cs.coverage, 0.0f);
      sum += Eigen::Array2d(cs.with_objects[0], cs.without_objects[0]);
    }
    return Eigen::Array2d(sum / count);
  };
  const Eigen::Array2d beside = walls({Vec3f(4.5f, 1.5f, 4), Vec3f(0.5f, 0, -2.7f).normalized()});
  const Eigen::Array2d across = walls({Vec3f(0, 1.5f, 0), Vec3f(-1, 0, 0)});
  EXPECT_NEAR(beside[1], 1.0, 0.05);
  EXPECT_NEAR(across[1], 1.0, 0.05);
  EXPECT_LT(beside[0], 0.8 * beside[1]);
  EXPECT_GT(across[0], 0.97 * across[1]);
}

// The scene below: a constant sky, a real floor and ceiling of albedo 0.8, 2 m apart, and the
// half-transparent black layer between them.
struct LayerBetweenPlanes {
  test::TempDir dir;
  CubeMap env = test::constant_cube(8, Rgb::Constant(1.0f));
  std::unique_ptr<EmbreeScene> layer;
  RenderInputs in;
  LayerBetweenPlanes() {
    dir.write("layer.mtl", "newmtl black\nKd 0 0 0\nd 0.5\n");
    Warnings w;
    std::vector<Mesh> meshes;
    meshes.push_back(load_obj(dir.write("layer.obj",
                                        "mtllib layer.mtl\nusemtl black\n"
                                        "v -1000 1 -1000\nv 1000 1 -1000\nv 1000 1 1000\nv -1000 1 1000\n"
                                        "f 1 2 3 4\n"),
                              w));
    layer = std::make_unique<EmbreeScene>(std::move(meshes));
    CatcherPlane ceiling = floor_plane(0.8f);
    ceiling.point = Vec3f(0, 2, 0), ceiling.normal = Vec3f(0, -1, 0);
    in.objects = layer.get();
    in.environment = &env;
    in.planes = {floor_plane(0.8f), ceiling};
  }
};

// The objects' change followed between real surfaces (photo_bounces, catcher_bounces). Between a real floor and
// a real ceiling 2 m above it, both infinite planes of albedo ρ = 0.8 in a constant sky L = 1, hangs
// a black layer at 1 m that stops half the rays through it (MTL `d 0.5`: stochastic opacity,
// τ = 0.5). A floor point sees only the ceiling: without objects it reflects N = ρ L. With them,
// over k real bounces the change Δ_k = W_k − N obeys, by symmetry (the ceiling's change is the
// floor's),
//   Δ_k = ρ (τ (1 + Δ_{k−1}) − 1),  Δ_0 = 0,
// since a cosine sample crosses the layer with probability τ and then sees the ceiling's photo plus
// its change: Δ_1 = −0.4, Δ_2 = −0.56, Δ_3 = −0.624, and Δ_∞ = ρ (τ − 1) / (1 − ρ τ) = −2/3.
TEST(Path, CatcherBouncesFollowTheObjectsChangeBetweenRealSurfaces) {
  LayerBetweenPlanes scene;
  RenderInputs& in = scene.in;
  const double rho = 0.8, tau = 0.5;
  double delta = 0;
  for (int k = 1; k <= 4; ++k) {
    const int bounces = k < 4 ? k : 1000;
    delta = rho * (tau * (1 + delta) - 1);
    const double expected = k < 4 ? delta : rho * (tau - 1) / (1 - rho * tau);
    // The camera sees the floor: its real bounces are photo_bounces (catcher_bounces those of an
    // object's paths, which take the same estimate).
    const auto path = make_integrator("path", in, {{"max_depth", 1000}, {"photo_bounces", bounces}});
    double sum = 0, sum2 = 0, without = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      Sampler s(11, std::uint64_t(k), std::uint64_t(i));
      const CameraSample cs = path->sample({Vec3f(0.1f, 0.5f, 0.2f), Vec3f(0, -1, 0)}, s);
      const double d = double(cs.with_objects[0]) - double(cs.without_objects[0]);
      sum += d, sum2 += d * d, without += cs.without_objects[0] / double(n);
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(without, rho, 1e-5) << bounces << " bounces";
    EXPECT_NEAR(mean, expected, 4 * se + 1e-4) << bounces << " bounces";
  }
}

// The change grid serves the photo's pixels every bounce of the objects' change. The same layer
// between floor and ceiling, in a room box 40 m across and 2 m high: with the grid (each node the
// mean of 64 estimates over catcher_bounces = 1000 real surfaces) the floor's change is Δ_∞ =
// −2/3 whatever photo_bounces is; without it, over photo_bounces = 1, Δ_1 = −0.4. The box's walls
// take the floor's cosine samples below 5.7° of elevation (1 % of them), where the symmetry above
// does not hold: at most 0.01 · ρ τ · 2/3 ≈ 0.003. A node's estimate spreads by about 1, so each
// of 64 is off by about 1/8 and the ~30 nodes that the pixel's samples read (0.6 m apart, the
// ceiling 2 m above) by 0.02 together, times ρ τ = 0.4: 0.009. Tolerance: 4 standard errors of
// the pixel's mean plus 0.012.
TEST(Path, TheChangeGridFollowsTheObjectsChangeOverEveryBounce) {
  LayerBetweenPlanes scene;
  RenderInputs& in = scene.in;
  in.room = RoomBox{Vec3f(-20, 0, -20), Vec3f(20, 2, 20), Vec3f(0, 1, 0), {}, std::nullopt};
  const double rho = 0.8, tau = 0.5;
  for (const int grid_samples : {64, 0}) {
    const double expected = grid_samples > 0 ? rho * (tau - 1) / (1 - rho * tau) : rho * (tau - 1);
    const auto path =
        make_integrator("path", in, {{"max_depth", 1000}, {"catcher_bounces", 1000}, {"change_grid", grid_samples}});
    double sum = 0, sum2 = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      Sampler s(13, std::uint64_t(grid_samples), std::uint64_t(i));
      const CameraSample cs = path->sample({Vec3f(0.1f, 0.5f, 0.2f), Vec3f(0, -1, 0)}, s);
      const double d = double(cs.with_objects[0]) - double(cs.without_objects[0]);
      sum += d, sum2 += d * d;
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, expected, 4 * se + 0.012) << "change_grid " << grid_samples;
  }
}

}  // namespace
}  // namespace insitu
