#include <gtest/gtest.h>

#include <random>

#include "light/cubemap.h"

namespace insitu {
namespace {

float id_value(int face, int i, int j, int n) { return float(face * 1000 + j * n + i); }

CubeMap id_cube(int n) {
  CubeMap cube(n);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) cube.set_texel(f, i, j, Rgb::Constant(id_value(f, i, j, n)));
  cube.update_borders();
  return cube;
}

struct Case {
  Vec3f dir;
  int face, i, j;
};

// Derived by hand from the DESIGN.md table on a 5×5 face: s = (sc/|ma| + 1)/2, so sc = ±0.9
// lands in texel 4 or 0 and sc = 0 in texel 2. One centre, one edge and one corner per face.
const Case kCases[] = {
    {{1, 0, 0}, kPosX, 2, 2},  {{1, 0, 0.9f}, kPosX, 0, 2},   {{1, 0.9f, -0.9f}, kPosX, 4, 0},
    {{-1, 0, 0}, kNegX, 2, 2}, {{-1, -0.9f, 0}, kNegX, 2, 4}, {{-1, 0.9f, 0.9f}, kNegX, 4, 0},
    {{0, 1, 0}, kPosY, 2, 2},  {{0, 1, -0.9f}, kPosY, 2, 0},  {{-0.9f, 1, 0.9f}, kPosY, 0, 4},
    {{0, -1, 0}, kNegY, 2, 2}, {{0.9f, -1, 0}, kNegY, 4, 2},  {{-0.9f, -1, -0.9f}, kNegY, 0, 4},
    {{0, 0, 1}, kPosZ, 2, 2},  {{0, 0.9f, 1}, kPosZ, 2, 0},   {{0.9f, -0.9f, 1}, kPosZ, 4, 4},
    {{0, 0, -1}, kNegZ, 2, 2}, {{0.9f, 0, -1}, kNegZ, 0, 2},  {{-0.9f, 0.9f, -1}, kNegZ, 4, 0},
};

TEST(CubeMap, CentreEdgeAndCornerDirectionsLandOnTheirTexel) {
  const int n = 5;
  const CubeMap cube = id_cube(n);
  for (const Case& c : kCases) {
    const FaceCoord fc = direction_to_face(c.dir * 3.0f);  // length does not matter
    EXPECT_EQ(fc.face, c.face) << c.dir.transpose();
    EXPECT_EQ(int(fc.s * float(n)), c.i) << c.dir.transpose();
    EXPECT_EQ(int(fc.t * float(n)), c.j) << c.dir.transpose();
    EXPECT_EQ(cube.lookup_nearest(c.dir)[0], id_value(c.face, c.i, c.j, n)) << c.dir.transpose();
  }
}

TEST(CubeMap, TexelDirectionRoundTrip) {
  for (int n : {1, 2, 7, 64}) {
    const CubeMap cube = id_cube(n);
    for (int f = 0; f < 6; ++f)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const Vec3f d = texel_direction(f, i, j, n);
          EXPECT_NEAR(d.norm(), 1.0f, 1e-6f);
          const FaceCoord fc = direction_to_face(d);
          ASSERT_EQ(fc.face, f);
          EXPECT_EQ(int(fc.s * float(n)), i);
          EXPECT_EQ(int(fc.t * float(n)), j);
          // Bilinear at a texel centre is the texel itself.
          EXPECT_NEAR(cube.lookup(d)[0], id_value(f, i, j, n), 0.05f);  // ids differ by >= 1; border ids by ~5000
        }
  }
}

TEST(CubeMap, ConstantCubeIsConstantEverywhere) {
  CubeMap cube(3);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) cube.set_texel(f, i, j, Rgb(0.5f, 2.0f, 1e5f));
  cube.update_borders();
  std::mt19937 rng(1);
  std::normal_distribution<float> g(0, 1);
  for (int k = 0; k < 10000; ++k) {
    const Rgb c = cube.lookup({g(rng), g(rng), g(rng)});
    EXPECT_FLOAT_EQ(c[0], 0.5f);
    EXPECT_FLOAT_EQ(c[1], 2.0f);
    EXPECT_FLOAT_EQ(c[2], 1e5f);
  }
  // The eight corners too.
  for (int c = 0; c < 8; ++c)
    EXPECT_FLOAT_EQ(cube.lookup({c & 1 ? 1.f : -1.f, c & 2 ? 1.f : -1.f, c & 4 ? 1.f : -1.f})[1], 2.0f);
}

// On either side of each of the 12 edges the bilinear lookup must agree: a point p on the edge
// (|p_a| = |p_b| = 1, |p_c| < 0.999) nudged into face a and into face b by ε. The bilinear function
// changes by at most (max texel difference) per texel, and 2ε in the face plane is ε·n texels.
TEST(CubeMap, LookupIsContinuousAcrossEveryEdge) {
  const int n = 8;
  CubeMap cube(n);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0, 1);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) cube.set_texel(f, i, j, Rgb(u(rng), u(rng), u(rng)));
  cube.update_borders();
  const float eps = 1e-5f;
  int edges = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b) {
      const int c = 3 - a - b;
      for (float sa : {-1.0f, 1.0f})
        for (float sb : {-1.0f, 1.0f}) {
          ++edges;
          for (int k = 0; k < 200; ++k) {
            Vec3f p = Vec3f::Zero();
            p[a] = sa;
            p[b] = sb;
            p[c] = -0.999f + 1.998f * u(rng);  // all the way into the corners
            Vec3f on_a = p, on_b = p;
            on_a[b] -= eps * sb;  // |p_a| = 1 stays the major axis: face a
            on_b[a] -= eps * sa;
            ASSERT_NE(direction_to_face(on_a).face, direction_to_face(on_b).face);
            const Rgb va = cube.lookup(on_a), vb = cube.lookup(on_b);
            EXPECT_LT((va - vb).abs().maxCoeff(), 4 * eps * n) << "edge " << a << b << " at " << p.transpose();
          }
        }
    }
  EXPECT_EQ(edges, 12);
}

}  // namespace
}  // namespace insitu
