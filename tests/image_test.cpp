// Images: reading, writing, EXIF, limits (core/image.h).
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <sys/resource.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "core/colour.h"
#include "core/error.h"
#include "core/exr_header.h"
#include "core/image.h"
#include "test_util.h"

namespace insitu {
namespace {

TEST(Image, SanitizeClampsAndCounts) {
  Image img(2, 1, 3);
  img.data = {1.0f, -2.0f, std::nanf(""), INFINITY, 1e-6f, 1e5f};
  EXPECT_EQ(sanitize(img), 3u);
  EXPECT_EQ(img.data, (std::vector<float>{1.0f, 0.0f, 0.0f, 0.0f, 1e-6f, 1e5f}));
}

TEST(Image, ExrKeepsHighDynamicRange) {
  test::TempDir dir;
  Image img(2, 1, 3);
  img.data = {1e-6f, 1.0f, 1e5f, 0.5f, 2.0f, 3.0f};
  write_image(dir.file("x.exr"), img);  // stored as 32-bit float (half would overflow at 65504)
  const ImageFile f = read_image_file(dir.file("x.exr"));
  EXPECT_FALSE(f.display_referred);
  for (std::size_t i = 0; i < img.data.size(); ++i) EXPECT_EQ(f.stored.data[i], img.data[i]);
}

TEST(Image, ErrorsNameTheFile) {
  test::TempDir dir;
  const std::string junk = dir.write("junk.png", "this is not a png");
  try {
    read_image_file(junk);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), junk);
  }
  try {
    read_image_file(dir.file("absent.jpg"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), dir.file("absent.jpg"));
    EXPECT_EQ(e.message(), "file not found");
  }
}

TEST(Image, FailedWriteLeavesNothing) {
  test::TempDir dir;
  // A folder where the file should go: rename fails, and the temporary file is removed.
  std::filesystem::create_directories(dir.file("taken.png"));
  std::filesystem::create_directories(dir.file("taken.png/inner"));
  EXPECT_THROW(write_image(dir.file("taken.png"), Image(2, 2, 3, 0.5f)), InputError);
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) files += e.is_regular_file();
  EXPECT_EQ(files, 0);
}

// Writes `values` (channels interleaved) with OpenImageIO directly, so that the layouts insitu never
// writes itself (tiles, a data window away from the origin, grey, RGBA) can be read back.
void write_with_oiio(const std::string& path, OIIO::ImageSpec spec, const std::vector<float>& values) {
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out && out->open(path, spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, values.data()));
  out->close();
}

std::vector<float> ramp(std::size_t n) {
  std::vector<float> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = 0.25f + float(i);
  return v;
}

TEST(Image, ReadsTiledExrWithAnOffsetDataWindow) {
  test::TempDir dir;
  OIIO::ImageSpec spec(37, 70, 4, OIIO::TypeDesc::FLOAT);  // 70 rows: two bands of 64 rows
  spec.x = 5;
  spec.y = -3;
  spec.full_x = 5;
  spec.full_y = -3;
  spec.tile_width = spec.tile_height = 16;
  const std::vector<float> rgba = ramp(37 * 70 * 4);
  write_with_oiio(dir.file("tiled.exr"), spec, rgba);
  const Image img = read_image_file(dir.file("tiled.exr")).stored;
  ASSERT_EQ(img.width, 37);
  ASSERT_EQ(img.height, 70);
  for (std::size_t i = 0; i < std::size_t(37 * 70); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(img.data[i * 3 + c], rgba[i * 4 + c]) << i;
}

TEST(Image, GreyIsRepeatedIntoRgb) {
  test::TempDir dir;
  const std::vector<float> grey = ramp(9 * 130);
  write_with_oiio(dir.file("grey.exr"), OIIO::ImageSpec(9, 130, 1, OIIO::TypeDesc::FLOAT), grey);
  const Image img = read_image_file(dir.file("grey.exr")).stored;
  ASSERT_EQ(img.data.size(), grey.size() * 3);
  for (std::size_t i = 0; i < grey.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(img.data[i * 3 + c], grey[i]);
}

// A 558-byte PNG whose header declares 11585² RGBA pixels (just under kMaxImagePixels) and whose
// data stops after ten rows: refused as corrupt, without first allocating the 2.1 GB the header
// implies (what the fuzzer found). ctest runs each test in its own process, so the peak resident
// size is this test's.
TEST(Image, TruncatedHugePngFailsWithoutAllocatingItsHeaderSize) {
  test::TempDir dir;
  const auto be32 = [](std::uint32_t v) {
    return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  };
  const auto chunk = [&](const std::string& type, const std::string& data) {
    const std::string body = type + data;
    return be32(std::uint32_t(data.size())) + body +
           be32(std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
  };
  const std::uint32_t side = 11585;
  std::string rows;
  for (int r = 0; r < 10; ++r) rows += '\0' + std::string(side * 4, '\x80');
  std::string deflated(compressBound(uLong(rows.size())), '\0');
  uLongf deflated_size = uLongf(deflated.size());
  ASSERT_EQ(compress(reinterpret_cast<Bytef*>(deflated.data()), &deflated_size,
                     reinterpret_cast<const Bytef*>(rows.data()), uLong(rows.size())), Z_OK);
  deflated.resize(deflated_size);
  const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) +
                          chunk("IHDR", be32(side) + be32(side) + std::string("\x08\x06\x00\x00\x00", 5)) +
                          chunk("IDAT", deflated) + chunk("IEND", "");
  const std::string path = dir.write("huge.png", png);
  EXPECT_THROW(read_image_file(path), InputError);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  EXPECT_LT(usage.ru_maxrss / 1024, 1024) << "peak resident MB";  // the header implies 3.7 GB
}

// A decompression bomb (the image fuzzer's find): a 677-byte EXR whose header declares 7995408 × 8
// pixels of one colour decodes honestly to 64 megapixels; it is refused from its header, naming
// the file, the size and the reason, before anything is decoded.
TEST(Image, DecompressionBombIsRefusedFromItsHeader) {
  const std::string path = test::test_data("bomb_64_megapixels.exr");
  try {
    read_image_file(path);
    FAIL() << "the bomb was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), path);
    EXPECT_NE(e.message().find("7995408x8 pixels in a file of 677 bytes"), std::string::npos) << e.what();
  }
  // The same pixels per byte below the floor of 16 megapixels are read (small constant images are real).
  test::TempDir dir;
  Image flat(4096, 4096, 3, 0.5f);
  const std::string small = dir.file("flat.exr");
  write_image(small, flat);
  EXPECT_EQ(read_image_file(small).stored.width, 4096);
}

// The bomb's size comes from OpenEXRCore's header alone, before OpenEXR's reader reserves line
// buffers for its 8-million-pixel rows (under the sanitizers that took more than the fuzzer's 10 s).
TEST(Image, ExrHeaderIsReadWithoutOpeningTheImage) {
  const auto bomb = exr_declared_size(test::test_data("bomb_64_megapixels.exr"));
  ASSERT_TRUE(bomb.has_value());
  EXPECT_EQ(bomb->first, 7995408);
  EXPECT_EQ(bomb->second, 8);
  test::TempDir dir;
  write_image(dir.file("a.exr"), Image(5, 3, 3, 1.0f));
  write_image(dir.file("a.png"), Image(5, 3, 3, 0.5f));
  EXPECT_EQ(exr_declared_size(dir.file("a.exr")), std::make_pair(std::int64_t(5), std::int64_t(3)));
  EXPECT_FALSE(exr_declared_size(dir.file("a.png")).has_value());
  EXPECT_FALSE(exr_declared_size(dir.file("missing.exr")).has_value());
}

// A name the system refuses (longer than NAME_MAX) is a one-line InputError naming it, not a
// filesystem_error (the OBJ fuzzer found it through a texture name).
TEST(Image, ANameTooLongIsAnInputError) {
  const std::string name = "/tmp/" + std::string(300, 'a') + ".png";
  try {
    read_image_file(name);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), name);
    EXPECT_NE(e.message().find("cannot access"), std::string::npos) << e.message();
  }
}

}  // namespace
}  // namespace insitu
