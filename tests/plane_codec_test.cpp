// Byte-shuffled planes in a zstd frame (render/plane_codec.h): a round trip, the shuffle's use
// (rounded floats compress to far less shuffled than interleaved), and frames that must be
// refused: another declared size, truncated, with bytes after the end, garbage. (A frame damaged
// within its blocks may still decode: the file's checksum is what refuses it, render/checkpoint.h.)
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <zstd.h>

#include "core/error.h"
#include "core/float_bits.h"
#include "render/plane_codec.h"

namespace insitu {
namespace {

std::vector<std::uint32_t> smooth_floats(std::size_t n, int bits) {
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  std::vector<std::uint32_t> words(n);
  for (std::size_t i = 0; i < n; ++i) {
    words[i] = float_bits(round_significand(1.0f + 0.5f * std::sin(float(i) * 1e-3f) + noise(rng), bits));
  }
  return words;
}

std::string frame_of(const std::vector<std::uint32_t>& a, const std::vector<std::uint8_t>& b) {
  PlaneWriter z(4 * a.size() + b.size());
  z.words(a);
  z.bytes(b.data(), b.size());
  return z.finish();
}

TEST(PlaneCodec, RoundTrip) {
  const std::vector<std::uint32_t> a = smooth_floats(100000, 23);
  const std::vector<std::uint8_t> b = {0, 1, 1, 0, 7};
  const std::string frame = frame_of(a, b);
  PlaneReader z(frame.data(), frame.size(), 4 * a.size() + b.size(), "f");
  EXPECT_EQ(z.words(a.size()), a);
  std::vector<std::uint8_t> back(b.size());
  z.bytes(back.data(), back.size());
  EXPECT_EQ(back, b);
  EXPECT_NO_THROW(z.finish());
}

// Noisy floats with 10 significand bits: shuffled, they compress to less than 0.9 of what the
// same words interleaved do (1.27 against 1.60 bytes a word when measured), and to under 1.5 of
// their 4 bytes (the 13 zero bits and the near-constant exponent byte go; unrounded: 2.8).
TEST(PlaneCodec, ShuffleIsWhatCompresses) {
  const std::vector<std::uint32_t> a = smooth_floats(1 << 18, 10);
  const std::string shuffled = frame_of(a, {});
  std::string plain(ZSTD_compressBound(4 * a.size()), '\0');
  plain.resize(ZSTD_compress(plain.data(), plain.size(), a.data(), 4 * a.size(), 3));
  EXPECT_LT(double(shuffled.size()), 0.9 * double(plain.size())) << shuffled.size() << " " << plain.size();
  EXPECT_LT(double(shuffled.size()) / double(a.size()), 1.5);
}

TEST(PlaneCodec, RefusesFramesThatAreNotWhatTheHeaderSays) {
  const std::vector<std::uint32_t> a = smooth_floats(5000, 23);
  const std::string frame = frame_of(a, {});
  EXPECT_THROW(PlaneReader(frame.data(), frame.size(), 4 * a.size() + 4, "f"), InputError);
  EXPECT_THROW(PlaneReader(frame.data(), frame.size(), 1ull << 40, "f"), InputError);
  // All zeros, the most compressible: well within 32768 bytes a byte of frame.
  const std::vector<std::uint32_t> zeros(1 << 22, 0);
  const std::string small = frame_of(zeros, {});
  EXPECT_NO_THROW(PlaneReader(small.data(), small.size(), 4 * zeros.size(), "f").words(zeros.size()));
  {
    PlaneReader z(frame.data(), frame.size() / 2, 4 * a.size(), "f");  // truncated
    EXPECT_THROW(z.words(a.size()), InputError);
  }
  {
    const std::string longer = frame + "x";
    PlaneReader z(longer.data(), longer.size(), 4 * a.size(), "f");
    z.words(a.size());
    EXPECT_THROW(z.finish(), InputError);
  }
  {
    PlaneReader z(frame.data(), frame.size(), 4 * a.size(), "f");
    z.words(a.size() - 1);  // the reader did not take all of it
    EXPECT_THROW(z.finish(), InputError);
  }
  const std::string garbage(64, '\x5a');
  EXPECT_THROW(PlaneReader(garbage.data(), garbage.size(), 16, "f"), InputError);
}

}  // namespace
}  // namespace insitu
