#include <gtest/gtest.h>

#include <random>

#include "cube_fixture.h"
#include "light/texel_geometry.h"
#include "light/plane_irradiance.h"

namespace insitu {
namespace {

const RoomBox kBox{Vec3f(-2.5f, 0, -3),
                   Vec3f(2.5f, 2.6f, 3),
                   Vec3f(-0.2f, 0.9f, -1.2f),
                   {{0, Vec3f(-2.5f, 0.9f, -2.2f), Vec3f(-2.5f, 2.1f, -0.6f)}},
                   std::nullopt};

// A closed room of constant radiance L, window or not, gives E = π L everywhere on the floor.
TEST(PlaneIrradiance, ConstantRoomGivesPiL) {
  const CubeMap cube = test::constant_cube(8, Rgb::Constant(0.7f));
  const RoomLight room(cube, kBox);
  const PlaneIrradiance floor(room, kBox, Vec3f::Zero(), Vec3f(0, 1, 0), 16, 256);
  for (const Vec3f& x : {Vec3f(0, 0, 0), Vec3f(-2.4f, 0, 2.9f), Vec3f(1.3f, 0, -1.7f)})
    EXPECT_NEAR(floor.at(x)[0], kPiF * 0.7f, 0.02f * kPiF * 0.7f) << x.transpose();
}

// The estimator against the slow, obviously correct one: ∫ L_room(x, ω) cos θ dω by uniform
// directions over the hemisphere (pdf 1/2π), many of them, with a spiky cube and a window.
TEST(PlaneIrradiance, EstimateAgreesWithBruteForce) {
  const CubeMap cube = test::random_cube(8, 5);
  const RoomLight room(cube, kBox);
  const Vec3f n(0, 1, 0);
  for (const Vec3f& x : {Vec3f(0.9f, 1e-3f, -2.0f), Vec3f(-1.5f, 1e-3f, 2.0f)}) {
    const int count = 400000;
    std::mt19937 rng(9);
    std::normal_distribution<float> g(0, 1);
    double sum = 0, sum2 = 0;
    for (int k = 0; k < count; ++k) {
      Vec3f w = Vec3f(g(rng), g(rng), g(rng)).normalized();
      if (w.dot(n) < 0) w = -w;
      const double v = 2 * kPi * room.radiance(x, w)[1] * w.dot(n);
      sum += v, sum2 += v * v;
    }
    const double mean = sum / count, se = std::sqrt((sum2 / count - mean * mean) / count);
    // The estimator's own noise: 16 independent estimates of 1024 samples each.
    double e_sum = 0, e_sum2 = 0;
    for (int r = 0; r < 16; ++r) {
      const double e = PlaneIrradiance::estimate(room, x, n, 1024, 100 + std::uint64_t(r))[1];
      e_sum += e, e_sum2 += e * e;
    }
    const double e_mean = e_sum / 16, e_se = std::sqrt((e_sum2 / 16 - e_mean * e_mean) / 15);
    EXPECT_NEAR(e_mean, mean, 4 * std::hypot(se, e_se)) << x.transpose();
  }
}

// The sun through the window: the floor where it lands receives its irradiance E_sun cos θ on top
// of the room's; the floor in the shade does not, and the grid keeps the two apart.
TEST(PlaneIrradiance, SunlitPatchStandsOut) {
  const Vec3f to_sun = Vec3f(-1.0f, 0.45f, 0.25f).normalized();
  const int n = 64;
  const CubeMap cube = test::sun_cube(n, to_sun, 0.1f, 1e4f);
  const FaceCoord sun = direction_to_face(to_sun);
  const int si = int(sun.s * n), sj = int(sun.t * n);
  const RoomBox box{
      kBox.min, kBox.max, kBox.capture, {{0, Vec3f(-2.5f, 0.9f, -2.2f), Vec3f(-2.5f, 2.3f, -0.2f)}}, std::nullopt};
  const RoomLight room(cube, box);
  const PlaneIrradiance floor(room, box, Vec3f::Zero(), Vec3f(0, 1, 0), 64, 256);
  // The sun's irradiance: its texel's radiance × solid angle × cos θ (the texel's centre direction).
  const double omega = texel_solid_angle(si, sj, n);
  const Vec3f d = texel_direction(sun.face, si, sj, n);
  const double e_sun = (1e4 - 0.1) * omega * d.y();
  // (0.9, 0, −2.6) sees the sun through the window; (0.9, 0, 1.5) meets the −x wall toward it.
  const double lit = floor.at(Vec3f(0.9f, 0, -2.6f))[0], shade = floor.at(Vec3f(0.9f, 0, 1.5f))[0];
  EXPECT_NEAR(shade, kPi * 0.1, 0.05 * kPi * 0.1);
  EXPECT_NEAR(lit - shade, e_sun, 0.1 * e_sun);
}

}  // namespace
}  // namespace insitu
