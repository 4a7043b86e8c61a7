#include <gtest/gtest.h>

#include <cmath>

#include "core/colour.h"
#include "core/error.h"
#include "core/image.h"
#include "test_util.h"

namespace insitu {
namespace {

// IEC 61966-2-1 by hand: 0.5 encoded is ((0.5+0.055)/1.055)^2.4 = 0.21404114; the linear
// segment meets the power curve at 0.04045 ↔ 0.0031308.
TEST(Colour, SrgbByHand) {
  EXPECT_NEAR(srgb_to_linear(0.5f), 0.21404114f, 1e-6f);
  EXPECT_NEAR(srgb_to_linear(0.04045f), 0.04045f / 12.92f, 1e-8f);
  EXPECT_EQ(srgb_to_linear(0.0f), 0.0f);
  EXPECT_NEAR(srgb_to_linear(1.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(linear_to_srgb(0.21404114f), 0.5f, 1e-6f);
  EXPECT_EQ(linear_to_srgb(2.0f), 1.0f);
  EXPECT_EQ(linear_to_srgb(-1.0f), 0.0f);
  EXPECT_EQ(linear_to_srgb(std::nanf("")), 0.0f);
  EXPECT_EQ(srgb_to_linear(std::nanf("")), 0.0f);
}

// Every 8-bit code survives decode + encode + rounding: what makes untouched pixels exact.
TEST(Colour, EightBitRoundTrip) {
  for (int k = 0; k < 256; ++k) {
    const float v = float(k) / 255.0f;
    EXPECT_EQ(int(std::lround(linear_to_srgb(srgb_to_linear(v)) * 255.0f)), k);
  }
}

}  // namespace
}  // namespace insitu
