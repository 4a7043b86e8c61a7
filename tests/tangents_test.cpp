// MikkTSpace tangents (render/tangents.h) and the shading normal's corrections
// (render/shading_normal.h), against frames derived by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "render/mesh.h"
#include "render/shading_normal.h"
#include "render/tangents.h"
#include "uv_sphere.h"

namespace insitu {
namespace {

// A mesh of triangles from corner lists, each corner its own vertex (welding finds the shared
// ones), with one normal for all.
Mesh mesh_of(const std::vector<std::array<Vec3f, 3>>& tris, const std::vector<std::array<Vec2f, 3>>& uvs,
             const Vec3f& normal) {
  Mesh m;
  m.normals.push_back(normal);
  for (std::size_t f = 0; f < tris.size(); ++f) {
    Triangle t{};
    for (std::size_t k = 0; k < 3; ++k) {
      m.positions.push_back(tris[f][k]);
      m.uvs.push_back(uvs[f][k]);
      t.v[k] = std::uint32_t(m.positions.size() - 1);
      t.n[k] = 0;
      t.t[k] = std::int32_t(m.uvs.size() - 1);
    }
    m.triangles.push_back(t);
  }
  m.materials.emplace_back();
  return m;
}

// A unit quad on the floor (normal +y) mapped u = x, v = −z: ∂p/∂u = +x, ∂p/∂v = −z = n × t, so the
// sign is +1 at every corner. Mirrored (u = −x), ∂p/∂u = −x and n × t = +z = −∂p/∂v: the sign is −1.
TEST(Tangents, AFloorQuadsTangentIsDpDuAndItsSignTheUvHandedness) {
  const Vec3f a(0, 0, 0), b(1, 0, 0), c(1, 0, -1), d(0, 0, -1);
  for (const float mirror : {1.0f, -1.0f}) {
    auto uv = [&](const Vec3f& p) { return Vec2f(mirror * p.x(), -p.z()); };
    const Mesh m = mesh_of({{a, b, c}, {a, c, d}}, {{uv(a), uv(b), uv(c)}, {uv(a), uv(c), uv(d)}}, Vec3f(0, 1, 0));
    const std::vector<Vec4f> t = mikktspace_tangents(m, 0);
    ASSERT_EQ(t.size(), 6u);
    for (const Vec4f& s : t) {
      EXPECT_TRUE(s.head<3>().isApprox(Vec3f(mirror, 0, 0), 1e-6f)) << s.transpose();
      EXPECT_EQ(s.w(), mirror);
    }
  }
}

// Two triangles share the vertex at the origin (normal +z) with different ∂p/∂u: +x in A (angle
// 90° there), (1, 1, 0)/√2 in B (angle 135°). The shared corner's tangent is their angle-weighted
// mean: normalize(π/2 · x̂ + 3π/4 · (1, 1, 0)/√2). The corners only A has keep A's tangent.
TEST(Tangents, ASharedVertexTakesTheAngleWeightedMean) {
  const Vec3f o(0, 0, 0), px(1, 0, 0), py(0, 1, 0), q(-1, -1, 0);
  const Vec2f uo(0, 0), ux(1, 0), uy(0, 1), uq(-1, 0);  // B: uv(q) = (−1, 0) makes ∂p/∂u = −(q − o)
  const Mesh m = mesh_of({{o, px, py}, {o, py, q}}, {{uo, ux, uy}, {uo, uy, uq}}, Vec3f(0, 0, 1));
  const std::vector<Vec4f> t = mikktspace_tangents(m, 0);
  const Vec3f expected = (kPiF / 2 * Vec3f(1, 0, 0) + 3 * kPiF / 4 * Vec3f(1, 1, 0).normalized()).normalized();
  EXPECT_TRUE(t[0].head<3>().isApprox(expected, 1e-5f)) << t[0].transpose();
  EXPECT_TRUE(t[3].head<3>().isApprox(expected, 1e-5f)) << t[3].transpose();
  EXPECT_TRUE(t[1].head<3>().isApprox(Vec3f(1, 0, 0), 1e-6f));               // px: A's alone
  EXPECT_TRUE(t[5].head<3>().isApprox(Vec3f(1, 1, 0).normalized(), 1e-6f));  // q: B's alone
  // The unweighted mean would differ by several degrees: the test can tell them apart.
  const Vec3f unweighted = (Vec3f(1, 0, 0) + Vec3f(1, 1, 0).normalized()).normalized();
  EXPECT_LT(expected.dot(unweighted), std::cos(2 * kPiF / 180));
  for (const Vec4f& s : t) EXPECT_EQ(s.w(), 1.0f);
}

// A smooth UV sphere (u = φ / 2π): away from the poles every tangent is the parallel's direction
// ∂p/∂φ, normalized, within the tessellation's error (the faces' ∂p/∂u differ from it by about
// half a segment's angle, and average it out to second order), and the frame is right-handed.
TEST(Tangents, ASpheresTangentsFollowItsParallels) {
  const float centre[3] = {0, 0, 0};
  const int rings = 24, segments = 48;
  const test::UvSphere s = test::make_uv_sphere(rings, segments, centre, 1.0f);
  const Mesh m = test::uv_sphere_mesh(s);
  const std::vector<Vec4f> t = mikktspace_tangents(m, 0);
  float worst_deg = 0, worst_seam_deg = 0;
  for (std::size_t f = 0; f < m.triangles.size(); ++f)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = m.triangles[f].v[k];
      const Vec3f& p = m.positions[v];
      if (std::abs(p.y()) > 0.97f) continue;  // the poles' fans
      // p = (sin θ cos φ, cos θ, −sin θ sin φ): ∂p/∂φ ∝ (−sin φ, 0, −cos φ) = (p_z, 0, −p_x)/sin θ.
      const Vec3f parallel = Vec3f(p.z(), 0, -p.x()).normalized();
      const float cos_angle = std::clamp(t[3 * f + k].head<3>().dot(parallel), -1.0f, 1.0f);
      const bool seam = m.uvs[v].x() == 0 || m.uvs[v].x() == 1;
      float& worst = seam ? worst_seam_deg : worst_deg;
      worst = std::max(worst, std::acos(cos_angle) * 180 / kPiF);
      EXPECT_EQ(t[3 * f + k].w(), 1.0f);
    }
  // Each face's ∂p/∂u is a chord of its ring, turned half a segment (180° / 48 = 3.75°) from the
  // parallels at its ends. Inside, the faces on either side cancel that to within a fraction; on
  // the seam (u = 0 and u = 1 are not welded) a vertex sees one side only, and keeps it.
  const float half_segment_deg = 180.0f / segments;
  EXPECT_LT(worst_deg, 0.1f * half_segment_deg);
  EXPECT_GT(worst_seam_deg, 0.8f * half_segment_deg);
  EXPECT_LT(worst_seam_deg, half_segment_deg);
}

// A triangle with two equal corners takes the space of a good corner at the same welded vertex.
TEST(Tangents, ADegenerateTriangleCopiesAGoodCornersSpace) {
  const Vec3f a(0, 0, 0), b(1, 0, 0), c(0, 0, -1);
  auto uv = [](const Vec3f& p) { return Vec2f(p.x(), -p.z()); };
  const Mesh m = mesh_of({{a, b, c}, {b, b, c}}, {{uv(a), uv(b), uv(c)}, {uv(b), uv(b), uv(c)}}, Vec3f(0, 1, 0));
  const std::vector<Vec4f> t = mikktspace_tangents(m, 0);
  for (std::size_t k = 3; k < 6; ++k) EXPECT_TRUE(t[k].isApprox(Vec4f(1, 0, 0, 1), 1e-6f)) << t[k].transpose();
}

// A mirroring transform keeps (n, t, w · n × t) the frame of the same surface directions: the
// bitangent still points along the mirrored ∂p/∂v.
TEST(Tangents, AMirrorFlipsTheSign) {
  const Vec3f a(0, 0, 0), b(1, 0, 0), c(0, 0, -1);
  auto uv = [](const Vec3f& p) { return Vec2f(p.x(), -p.z()); };
  Mesh m = mesh_of({{a, b, c}}, {{uv(a), uv(b), uv(c)}}, Vec3f(0, 1, 0));
  m.tangents = mikktspace_tangents(m, 0);
  Mat4d mirror = Mat4d::Identity();
  mirror(0, 0) = -1;  // x ↦ −x: ∂p/∂u becomes −x, ∂p/∂v stays −z, n stays +y
  transform_mesh(m, mirror);
  const Vec3f t = m.tangents[0].head<3>(), n = m.normals[0];
  EXPECT_TRUE(t.isApprox(Vec3f(-1, 0, 0)));
  EXPECT_TRUE((m.tangents[0].w() * n.cross(t)).isApprox(Vec3f(0, 0, -1)));
}

// The texel (½, ½, 1) is the unmapped normal; (½ + ½ sin α, ½, ½ + ½ cos α) tilts it by α toward the
// tangent; the green channel tilts it toward the bitangent w · n × t.
TEST(ShadingNormal, ATangentSpaceTexelTiltsTheNormal) {
  const Vec3f n(0, 1, 0);
  const Vec4f t(1, 0, 0, 1);
  EXPECT_TRUE(tangent_space_normal(n, t, Rgb(0.5f, 0.5f, 1)).isApprox(n));
  const float alpha = 0.3f;
  const Rgb tilt(0.5f + 0.5f * std::sin(alpha), 0.5f, 0.5f + 0.5f * std::cos(alpha));
  EXPECT_TRUE(tangent_space_normal(n, t, tilt).isApprox(Vec3f(std::sin(alpha), std::cos(alpha), 0), 1e-6f));
  const Rgb green(0.5f, 0.5f + 0.5f * std::sin(alpha), 0.5f + 0.5f * std::cos(alpha));
  // n × t = (0, 1, 0) × (1, 0, 0) = (0, 0, −1).
  EXPECT_TRUE(tangent_space_normal(n, t, green).isApprox(Vec3f(0, std::cos(alpha), -std::sin(alpha)), 1e-6f));
  EXPECT_TRUE(
      tangent_space_normal(n, Vec4f(1, 0, 0, -1), green).isApprox(Vec3f(0, std::cos(alpha), std::sin(alpha)), 1e-6f));
  // Strength 0 is the unmapped normal, 1 the mapped one, ½ their normalized midpoint.
  const Vec3f mapped = tangent_space_normal(n, t, tilt);
  EXPECT_TRUE(with_strength(n, mapped, 0).isApprox(n));
  EXPECT_TRUE(with_strength(n, mapped, 1) == mapped);
  EXPECT_TRUE(with_strength(n, mapped, 0.5f).isApprox((n + mapped).normalized(), 1e-6f));
}

// A shading normal whose mirror direction stays above the surface is kept; one tilted away from a
// grazing viewer is turned, in the plane of ng and n, until the mirror direction's height over the
// surface is min(0.9 ng · wo, 0.01) (the definition in shading_normal.h, checked here directly).
TEST(ShadingNormal, AValidReflectionKeepsTheMirrorDirectionAboveTheSurface) {
  const Vec3f ng(0, 0, 1);
  const Vec3f wo = Vec3f(1, 0, 0.1f).normalized();
  const Vec3f fine = Vec3f(0.1f, 0, 1).normalized();
  EXPECT_EQ(valid_reflection_normal(ng, wo, fine), fine);
  const Vec3f tilted = Vec3f(-0.5f, 0.2f, 1).normalized();  // mirrors wo below the surface
  ASSERT_LT(ng.dot(2 * tilted.dot(wo) * tilted - wo), 0.0f);
  const Vec3f n = valid_reflection_normal(ng, wo, tilted);
  EXPECT_NEAR(n.norm(), 1.0f, 1e-5f);
  EXPECT_NEAR(ng.dot(2 * n.dot(wo) * n - wo), std::min(0.9f * ng.dot(wo), 0.01f), 1e-4f);
  EXPECT_NEAR(n.dot(ng.cross(tilted).normalized()), 0.0f, 1e-5f);  // in the plane of ng and n
  EXPECT_GT(n.dot(ng), tilted.dot(ng));                            // turned toward ng
}

}  // namespace
}  // namespace insitu
