#include <gtest/gtest.h>

#include <random>

#include "light/equirect.h"
#include "test_util.h"

namespace insitu {
namespace {

// The layout of ../shared/data/hdri, by hand: world +X (Blender +X) is the centre column;
// world −Z (Blender +Y, azimuth +90°) is at u = 0.25; world +Z at u = 0.75; up is the top row.
TEST(Equirect, LayoutByHand) {
  auto uv = [](float x, float y, float z) { return direction_to_equirect(Vec3f(x, y, z).normalized()); };
  EXPECT_NEAR(uv(1, 0, 0).x(), 0.5f, 1e-6f);
  EXPECT_NEAR(uv(1, 0, 0).y(), 0.5f, 1e-6f);
  EXPECT_NEAR(uv(0, 0, -1).x(), 0.25f, 1e-6f);
  EXPECT_NEAR(uv(0, 0, 1).x(), 0.75f, 1e-6f);
  EXPECT_NEAR(std::fmod(uv(-1, 0, 0).x(), 1.0f), 0.0f, 1e-6f);
  EXPECT_NEAR(uv(0, 1, 0).y(), 0.0f, 1e-6f);
  EXPECT_NEAR(uv(0, -1, 0).y(), 1.0f, 1e-6f);
}

TEST(Equirect, RoundTrip) {
  std::mt19937 rng(3);
  std::normal_distribution<float> g(0, 1);
  for (int k = 0; k < 1000; ++k) {
    const Vec3f d = Vec3f(g(rng), g(rng), g(rng)).normalized();
    const Vec2f uv = direction_to_equirect(d);
    EXPECT_LT((equirect_to_direction(uv.x(), uv.y()) - d).norm(), 1e-5f);
  }
}

TEST(Equirect, StripRoundTrip) {
  CubeMap cube(4);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) cube.set_texel(f, i, j, Rgb(float(f), float(i), float(j)));
  const CubeMap back = cube_from_strip(cube_to_strip(cube));
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) EXPECT_TRUE((back.texel(f, i, j) == cube.texel(f, i, j)).all());
}

// The brightest texel of a real HDRI lands where the equirect says: the cube built from it has
// its maximum in the same direction (within a texel).
TEST(Equirect, RealHdriBrightestDirectionSurvivesConversion) {
  INSITU_REQUIRE_SHARED();
  Image img = linearize(read_image_file(test::shared_data() + "/hdri/sunset.exr"));
  int bx = 0, by = 0;
  float best = -1;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (luminance(img.rgb(x, y)) > best) {
        best = luminance(img.rgb(x, y));
        bx = x;
        by = y;
      }
  const Vec3f d_sun =
      equirect_to_direction((float(bx) + 0.5f) / float(img.width), (float(by) + 0.5f) / float(img.height));
  const CubeMap cube = cube_from_equirect(img, 64);
  Vec3f d_best = Vec3f::Zero();
  best = -1;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i)
        if (luminance(cube.texel(f, i, j)) > best) {
          best = luminance(cube.texel(f, i, j));
          d_best = texel_direction(f, i, j, 64);
        }
  // A texel of a 64² face spans at most ~1.8°; the equirect pixel 0.7°.
  EXPECT_GT(d_sun.dot(d_best), std::cos(4.0f * kPiF / 180.0f));
}

}  // namespace
}  // namespace insitu
