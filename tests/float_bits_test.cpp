// Rounding a float32 to fewer significand bits (core/float_bits.h): the bit trick against frexp
// and ldexp over random floats of every exponent, ties to even, the carry into the exponent, and
// the values it must leave alone.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/float_bits.h"

namespace insitu {
namespace {

TEST(FloatBits, MatchesTheReferenceOnNormalNumbers) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::uint32_t> word;
  int tested = 0;
  for (int i = 0; i < 200000; ++i) {
    const float x = bits_float(word(rng));
    if (!std::isnormal(x)) continue;
    for (int bits : {1, 7, 10, 16, 22}) {
      ASSERT_EQ(round_significand(x, bits), round_significand_reference(x, bits)) << x << " " << bits;
      ++tested;
    }
  }
  EXPECT_GT(tested, 900000);
}

TEST(FloatBits, TiesGoToEvenAndCarriesStepTheExponent) {
  // 1 + 2^-11 lies halfway between 1 and 1 + 2^-10: even is 1. 1 + 3·2^-11 goes up to 1 + 2^-9.
  EXPECT_EQ(round_significand(1.0f + std::ldexp(1.0f, -11), 10), 1.0f);
  EXPECT_EQ(round_significand(1.0f + 3 * std::ldexp(1.0f, -11), 10), 1.0f + std::ldexp(1.0f, -9));
  EXPECT_EQ(round_significand(std::nextafter(2.0f, 0.0f), 10), 2.0f);
  EXPECT_EQ(round_significand(-1.25f, 10), -1.25f);
  // Within binary16's relative precision, 2^-11.
  EXPECT_NEAR(round_significand(0.1f, 10), 0.1f, 0.1f * std::ldexp(1.0f, -11));
}

TEST(FloatBits, LeavesWhatItCannotRound) {
  const float inf = std::numeric_limits<float>::infinity(), big = std::numeric_limits<float>::max();
  EXPECT_EQ(round_significand(inf, 10), inf);
  EXPECT_TRUE(std::isnan(round_significand(std::nanf(""), 10)));
  EXPECT_EQ(round_significand(big, 10), big);  // rounding up would overflow
  EXPECT_EQ(round_significand(0.0f, 10), 0.0f);
  EXPECT_EQ(round_significand(0.3f, 23), 0.3f);
}

}  // namespace
}  // namespace insitu
