#include <gtest/gtest.h>

#include <cmath>

#include "chi2.h"
#include "cube_fixture.h"
#include "core/sampler.h"
#include "core/sampling.h"
#include "integrators/registry.h"
#include "obj_sphere.h"
#include "render/embree_scene.h"
#include "render/object_cones.h"
#include "test_util.h"

namespace insitu {
namespace {

// A mesh whose bounding sphere ObjectCones takes: the 8 corners of a cube of half-size h about c
// (radius h√3), two triangles on one face (ObjectCones reads the triangles' vertices only).
Mesh cube_corners(const Vec3f& c, float h) {
  Mesh m;
  for (int k = 0; k < 8; ++k)
    m.positions.push_back(c + h * Vec3f(k & 1 ? 1.0f : -1.0f, k & 2 ? 1.0f : -1.0f, k & 4 ? 1.0f : -1.0f));
  m.triangles.push_back({{0, 1, 3}, {-1, -1, -1}, {-1, -1, -1}, 0});
  m.triangles.push_back({{4, 5, 6}, {-1, -1, -1}, {-1, -1, -1}, 0});
  m.triangles.push_back({{7, 2, 6}, {-1, -1, -1}, {-1, -1, -1}, 0});
  m.materials.emplace_back();
  return m;
}

// Equal-area bins over the sphere: z = cos θ in nz rows, φ in nphi columns.
constexpr int kNz = 48, kNphi = 96;
int bin_of(const Vec3f& d) {
  const int iz = std::clamp(int((d.z() + 1) / 2 * kNz), 0, kNz - 1);
  const float phi = std::atan2(d.y(), d.x()) + kPiF;
  const int ip = std::clamp(int(phi / (2 * kPiF) * kNphi), 0, kNphi - 1);
  return iz * kNphi + ip;
}

// ∫ pdf dω over each bin, by the midpoint rule on q × q points of (z, φ) (dω = dz dφ).
template <class Pdf>
std::vector<double> bin_integrals(const Pdf& pdf, int q) {
  std::vector<double> out(kNz * kNphi);
  const double dz = 2.0 / (kNz * q), dphi = 2 * kPi / (kNphi * q);
  for (int iz = 0; iz < kNz * q; ++iz)
    for (int ip = 0; ip < kNphi * q; ++ip) {
      const double z = -1 + (iz + 0.5) * dz, phi = -kPi + (ip + 0.5) * dphi, r = std::sqrt(1 - z * z);
      const Vec3f d(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
      out[std::size_t((iz / q) * kNphi + ip / q)] += pdf(d) * dz * dphi;
    }
  return out;
}

// Two overlapping spheres above a surface and one wholly below it (not used): the mixture of the
// cosine and the cones draws directions with the density it states, and that density integrates
// to 1 (the overlap counted twice, as sampling from either cone reaches it).
TEST(ObjectCones, TheMixtureDrawsDirectionsWithTheDensityItStates) {
  std::vector<Mesh> meshes;
  meshes.push_back(cube_corners({1.0f, 0.5f, 2.0f}, 0.4f));
  meshes.push_back(cube_corners({1.5f, 0.2f, 2.2f}, 0.5f));
  meshes.push_back(cube_corners({0.0f, 0.0f, -3.0f}, 0.5f));
  const ObjectCones cones(meshes);
  ASSERT_EQ(cones.spheres().size(), 3u);
  const Vec3f x = Vec3f::Zero(), n(0, 0, 1);
  const ReflectedSampling mix(cones, 0.5f, x, n);
  EXPECT_GT(mix.cone_share(), 0.4f);
  EXPECT_LT(mix.cone_share(), 0.5f);
  const std::vector<double> integral = bin_integrals([&](const Vec3f& d) { return mix.pdf(d); }, 12);
  double total = 0;
  for (double v : integral) total += v;
  EXPECT_NEAR(total, 1.0, 2e-3);
  const int count = 1000000;
  std::vector<double> observed(integral.size()), expected(integral.size());
  for (int k = 0; k < count; ++k) {
    Sampler s(3, 0, std::uint64_t(k));
    const float u0 = s.next(), u1 = s.next(), u2 = s.next();
    const Vec3f d = mix.sample(u0, u1, u2);
    ASSERT_NEAR(d.norm(), 1.0f, 1e-5f);
    ASSERT_GT(mix.pdf(d), 0.0f) << "a drawn direction has density 0";
    observed[std::size_t(bin_of(d))] += 1;
  }
  for (std::size_t b = 0; b < integral.size(); ++b) expected[b] = integral[b] * count;
  EXPECT_LT(test::chi2_score_of(observed, expected), 4.0);
}

// A small object far off: its cone's solid angle is 2π(1 − cos θ) to float precision, where
// 1 − √(1 − sin²θ) in float would cancel to 0 (sin²θ = 2.5·10⁻⁷ here).
TEST(ObjectCones, AFarSmallObjectsConeKeepsItsSolidAngle) {
  std::vector<Mesh> meshes;
  meshes.push_back(cube_corners({0.0f, 2000.0f, 0.0f}, 1.0f / std::sqrt(3.0f)));
  const ObjectCones cones(meshes);
  const double r = cones.spheres()[0].radius, d = 2000.0;
  const double exact = 2 * kPi * (r * r / (d * d)) / (1 + std::sqrt(1 - r * r / (d * d)));
  EXPECT_NEAR(cones.solid_angle(Vec3f::Zero(), Vec3f(0, 1, 0)) / exact, 1.0, 1e-4);
  // Below the surface, or around the point: no cone.
  EXPECT_EQ(cones.solid_angle(Vec3f::Zero(), Vec3f(0, -1, 0)), 0.0f);
  EXPECT_EQ(cones.solid_angle(Vec3f(0, 2000, 0), Vec3f(0, 1, 0)), 0.0f);
}

// A black ball of radius r at height h above a floor point, under a uniform sky L: it blocks the
// spherical cap of sin θ = r/h about the normal, ∫cap cos θ dω = π sin²θ, so the change there is
//   Δ = W − N = −ρ L sin²θ.
// Cosine samples find the cap with probability p = sin²θ and add −ρL each time: a per-sample
// variance of (ρL)² p (1 − p). Drawn toward the ball in every other sample, the estimate's variance
// falls below a quarter of that (about 0.03 of it here); the mean stays the closed form.
TEST(ObjectCones, AFarBallsChangeOnTheFloorIsFoundInEverySample) {
  test::TempDir dir;
  const float r = 0.5f, h = 3.0f, rho = 0.5f;
  Warnings w;
  std::vector<Mesh> meshes;
  meshes.push_back(load_obj(test::write_obj_sphere(dir, "ball", {0, h, 0}, r, "Kd 0 0 0\n", 64), w));
  const EmbreeScene scene(std::move(meshes));
  const CubeMap env = test::constant_cube(8, Rgb(1, 1, 1));
  RenderInputs in;
  in.objects = &scene;
  in.environment = &env;
  CatcherPlane floor;
  floor.point = Vec3f::Zero();
  floor.normal = Vec3f(0, 1, 0);
  floor.albedo_from_photo = false;
  floor.albedo = Rgb(rho, rho, rho);
  floor.irradiance = Rgb::Constant(kPiF);
  in.planes.push_back(floor);
  const auto path = make_integrator("path", in);
  const Ray ray{{3.0f, 0.5f, 0.0f}, Vec3f(-3.0f, -0.5f, 0.0f).normalized()};
  double sum = 0, sum2 = 0;
  const int count = 200000;
  for (int k = 0; k < count; ++k) {
    Sampler s(5, 0, std::uint64_t(k));
    const CameraSample cs = path->sample(ray, s);
    const double delta = double(cs.with_objects[0]) - double(cs.without_objects[0]);
    sum += delta, sum2 += delta * delta;
  }
  const double mean = sum / count, var = sum2 / count - mean * mean, se = std::sqrt(var / count);
  const double p = double(r) * r / (double(h) * h), exact = -double(rho) * p;
  // The 64-ring sphere is inscribed in the true one: its cap is smaller by under 0.5 %.
  EXPECT_NEAR(mean, exact, 4 * se + 0.005 * std::abs(exact));
  EXPECT_LT(var, 0.25 * double(rho) * rho * p * (1 - p));
}

}  // namespace
}  // namespace insitu
