#include <gtest/gtest.h>

#include <random>

#include "output/image_compare.h"

namespace insitu {
namespace {

Image noise_image(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, 1);
  Image img(w, h, 3);
  for (float& v : img.data) v = u(rng);
  return img;
}

TEST(Compare, IdenticalImages) {
  const Image a = noise_image(40, 30, 1);
  const CompareResult r = compare_images(a, a);
  EXPECT_EQ(r.whole.rmse, 0.0);
  EXPECT_EQ(r.whole.max_error, 0.0);
  EXPECT_NEAR(r.whole.ssim, 1.0, 1e-9);
  EXPECT_EQ(r.whole.pixels, 1200);
}

// B = A + 0.1 in every channel: RMSE = max error = 0.1 exactly, relative RMSE = 0.1/RMS(B).
TEST(Compare, ConstantOffsetByHand) {
  const Image a = noise_image(20, 10, 2);
  Image b = a;
  double ref = 0;
  for (float& v : b.data) {
    v += 0.1f;
    ref += double(v) * v;
  }
  const CompareResult r = compare_images(a, b);
  EXPECT_NEAR(r.whole.rmse, 0.1, 1e-6);
  EXPECT_NEAR(r.whole.max_error, 0.1, 1e-6);
  EXPECT_NEAR(r.whole.relative_rmse, 0.1 / std::sqrt(ref / double(b.data.size())), 1e-6);
  EXPECT_LT(r.whole.ssim, 1.0);
}

// A mask selects the region that differs.
TEST(Compare, MaskSelectsARegion) {
  const Image a = noise_image(20, 20, 3);
  Image b = a, mask(20, 20, 1, 0.0f);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 20; ++x) {
      b.at(x, y)[0] += 0.5f;
      *mask.at(x, y) = 1.0f;
    }
  const CompareResult r = compare_images(a, b, &mask);
  ASSERT_TRUE(r.masked.has_value());
  EXPECT_EQ(r.masked->pixels, 200);
  // Inside: one channel of three off by 0.5: RMSE = 0.5/√3; over the image, half of that spread.
  EXPECT_NEAR(r.masked->rmse, 0.5 / std::sqrt(3.0), 1e-6);
  EXPECT_NEAR(r.whole.rmse, 0.5 / std::sqrt(6.0), 1e-6);
  const Image pic = comparison_picture(a, b, r);
  EXPECT_GT(pic.width, 3 * 20);
}

}  // namespace
}  // namespace insitu
