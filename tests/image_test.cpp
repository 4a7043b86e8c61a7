// Images: reading, writing, EXIF, limits (core/image.h).
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

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

// A bilinear interpolation reproduces a function linear in x and y exactly between pixel centres,
// and holds the far edge's value there (its neighbour beyond the edge is itself).
TEST(Image, BilinearRgbIsExactOnALinearRamp) {
  Image img(4, 3, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) img.set_rgb(x, y, Rgb(float(x), float(2 * y), float(x + y)));
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {0.25, 1.5}, {2.75, 0.5}, {1.5, 1.75}}) {
    const Rgb c = bilinear_rgb(img, x, y);
    EXPECT_NEAR(c[0], x, 1e-6);
    EXPECT_NEAR(c[1], 2 * y, 1e-6);
    EXPECT_NEAR(c[2], x + y, 1e-6);
  }
  const Rgb corner = bilinear_rgb(img, 3.0, 2.0);
  EXPECT_FLOAT_EQ(corner[0], 3.0f);
  EXPECT_FLOAT_EQ(corner[1], 4.0f);
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

// A texture keeps an 8-bit file's bytes: exactly the bytes written, colour and alpha, whether read
// from the file or from memory, and the float reading of the same file is those bytes / 255. A
// 16-bit file is read as floats.
TEST(Image, TextureKeepsAnEightBitFilesBytes) {
  test::TempDir dir;
  const int w = 7, h = 5;
  std::vector<float> rgba(std::size_t(w) * h * 4);
  for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = float((i * 37 + 11) % 256) / 255.0f;
  OIIO::ImageSpec spec(w, h, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // the colour written as given, not divided by alpha
  write_with_oiio(dir.file("t.png"), spec, rgba);
  std::ifstream in(dir.file("t.png"), std::ios::binary);
  const std::vector<unsigned char> encoded((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const Image floats = read_image_file(dir.file("t.png"), PixelGrid::kAsStored).stored;
  for (const ImageFile& file : {read_texture_file(dir.file("t.png"), AlphaChannel::kKeep),
                                read_texture_memory("t.png", encoded, AlphaChannel::kKeep)}) {
    ASSERT_TRUE(file.stored.empty() && file.alpha.empty());
    ASSERT_EQ(file.stored_bytes.width, w);
    ASSERT_EQ(file.stored_bytes.height, h);
    ASSERT_EQ(file.stored_bytes.channels, 3);
    ASSERT_EQ(file.alpha_bytes.channels, 1);
    EXPECT_TRUE(file.display_referred);
    for (std::size_t p = 0; p < std::size_t(w) * h; ++p) {
      for (std::size_t c = 0; c < 3; ++c) {
        ASSERT_EQ(file.stored_bytes.data[p * 3 + c], ((p * 4 + c) * 37 + 11) % 256);
        ASSERT_FLOAT_EQ(float(file.stored_bytes.data[p * 3 + c]) / 255.0f, floats.data[p * 3 + c]);
      }
      ASSERT_EQ(file.alpha_bytes.data[p], ((p * 4 + 3) * 37 + 11) % 256);
    }
  }
  EXPECT_TRUE(read_texture_file(dir.file("t.png")).alpha_bytes.empty());  // not asked for
  write_with_oiio(dir.file("t16.png"), OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::UINT16),
                  std::vector<float>(w * h * 3, 0.5f));
  const ImageFile sixteen = read_texture_file(dir.file("t16.png"));
  EXPECT_TRUE(sixteen.stored_bytes.empty());
  ASSERT_EQ(sixteen.stored.data.size(), std::size_t(w) * h * 3);
  EXPECT_NEAR(sixteen.stored.data[0], 32768.0f / 65535.0f, 1e-6f);
}

// Where the stored pixel (x, y) of a w × h image is shown under EXIF orientation o, from the
// tag's definition (TIFF 6.0, tag 274: which visual side the 0th row and the 0th column are).
std::pair<int, int> shown_at(int o, int x, int y, int w, int h) {
  switch (o) {
    case 2:
      return {w - 1 - x, y};  // row 0 top, column 0 right: mirrored
    case 3:
      return {w - 1 - x, h - 1 - y};  // row 0 bottom, column 0 right: turned 180°
    case 4:
      return {x, h - 1 - y};  // row 0 bottom, column 0 left: flipped
    case 5:
      return {y, x};  // row 0 left, column 0 top: transposed
    case 6:
      return {h - 1 - y, x};  // row 0 right, column 0 top: turned 90° clockwise
    case 7:
      return {h - 1 - y, w - 1 - x};  // row 0 right, column 0 bottom: transverse
    case 8:
      return {y, w - 1 - x};  // row 0 left, column 0 bottom: turned 90° anticlockwise
    default:
      return {x, y};
  }
}

// A phone that stores the orientation tag instead of turning its pixels: the image is read as
// shown. The same pixels are written with each tag and without one; JPEG decodes identical data
// identically, so every shown pixel must equal the untagged file's pixel the tag maps there.
TEST(Image, ExifOrientationIsApplied) {
  test::TempDir dir;
  const int w = 24, h = 16;
  std::vector<float> values(std::size_t(w) * h * 3);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = float((i * 37) % 251) / 255.0f;
  write_with_oiio(dir.file("plain.jpg"), OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::UINT8), values);
  const ImageFile plain = read_image_file(dir.file("plain.jpg"));
  ASSERT_EQ(plain.orientation, 1);
  for (int o = 1; o <= 8; ++o) {
    OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("Orientation", o);
    const std::string path = dir.file(fmt::format("tagged{}.jpg", o));
    write_with_oiio(path, spec, values);
    const ImageFile tagged = read_image_file(path);
    ASSERT_EQ(tagged.orientation, o);
    const auto [sw, sh] = o >= 5 ? std::pair(h, w) : std::pair(w, h);
    ASSERT_EQ(tagged.stored.width, sw) << o;
    ASSERT_EQ(tagged.stored.height, sh) << o;
    EXPECT_EQ(read_image_size(path), std::pair(sw, sh)) << o;
    const ImageFile texture = read_image_file(path, PixelGrid::kAsStored);  // UVs address the stored grid
    ASSERT_EQ(texture.orientation, 1);
    ASSERT_EQ(texture.stored.data, plain.stored.data) << o;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const auto [xs, ys] = shown_at(o, x, y, w, h);
        ASSERT_TRUE((tagged.stored.rgb(xs, ys) == plain.stored.rgb(x, y)).all())
            << "orientation " << o << " at " << x << "," << y;
      }
  }
}

// The process's peak resident size since the last reset_peak_rss(), in MB (Linux: VmHWM).
long peak_resident_mb() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6)) / 1024;
  return -1;
}
// Writing 5 to clear_refs resets the peak (Linux ≥ 4.0): the suite runs many tests in a process.
bool reset_peak_rss() { return bool(std::ofstream("/proc/self/clear_refs") << "5"); }

// A 558-byte PNG whose header declares 11585² RGBA pixels (just under kMaxImagePixels) and whose
// data stops after ten rows: refused as corrupt, without first allocating the 2.1 GB the header
// implies (what the fuzzer found). The peak resident size is measured from a reset before it.
TEST(Image, TruncatedHugePngFailsWithoutAllocatingItsHeaderSize) {
  test::TempDir dir;
  const auto be32 = [](std::uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; };
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
                     reinterpret_cast<const Bytef*>(rows.data()), uLong(rows.size())),
            Z_OK);
  deflated.resize(deflated_size);
  const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) +
                          chunk("IHDR", be32(side) + be32(side) + std::string("\x08\x06\x00\x00\x00", 5)) +
                          chunk("IDAT", deflated) + chunk("IEND", "");
  const std::string path = dir.write("huge.png", png);
  ASSERT_TRUE(reset_peak_rss());
  const long before_mb = peak_resident_mb();
  EXPECT_THROW(read_image_file(path), InputError);
  EXPECT_THROW(read_texture_file(path), InputError);                      // the same, read as bytes
  EXPECT_LT(peak_resident_mb() - before_mb, 1024) << "peak resident MB";  // the header implies 3.7 GB
}

// Sets the data window of an EXR written by OpenImageIO (attribute "dataWindow", type "box2i",
// 16 bytes: xMin yMin xMax yMax, little-endian) to width × height: the file becomes a header
// declaring what its data does not hold, the fuzzer's kind of input.
std::string with_data_window(const std::string& path, std::int32_t width, std::int32_t height) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string key("dataWindow\0box2i\0\x10\0\0\0", 21);
  const std::size_t at = bytes.find(key);
  if (at == std::string::npos) return "";
  const std::int32_t box[4] = {0, 0, width - 1, height - 1};
  std::memcpy(&bytes[at + key.size()], box, sizeof box);
  const std::string out = path + ".patched.exr";
  std::ofstream(out, std::ios::binary) << bytes;
  return out;
}

// The image fuzzer's first bomb, remade: a 16 × 8 constant EXR whose header declares 7995408 × 8
// pixels (64 megapixels of R, G, B float: 768 MB) in a few hundred bytes. Refused from its header,
// naming the file, the size and the reason, before anything is decoded.
std::string write_bomb(const test::TempDir& dir) {
  write_with_oiio(dir.file("b.exr"), OIIO::ImageSpec(16, 8, 3, OIIO::TypeDesc::FLOAT),
                  std::vector<float>(16 * 8 * 3, 0.8f));
  return with_data_window(dir.file("b.exr"), 7995408, 8);
}

TEST(Image, DecompressionBombIsRefusedFromItsHeader) {
  test::TempDir dir;
  const std::string path = write_bomb(dir);
  ASSERT_FALSE(path.empty());
  const std::string expected =
      fmt::format("7995408x8 pixels of 12 bytes (768 MB) in a file of {} bytes", std::filesystem::file_size(path));
  try {
    read_image_file(path);
    FAIL() << "the bomb was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), path);
    EXPECT_NE(e.message().find(expected), std::string::npos) << e.what();
  }
  // A constant image below the floor of 64 MiB is read (small constant images are real).
  Image flat(4096, 4096, 3, 0.5f);
  const std::string small = dir.file("flat.exr");
  write_image(small, flat);
  EXPECT_EQ(read_image_file(small).stored.width, 4096);
}

// The bomb's size comes from OpenEXRCore's header alone, before OpenEXR's reader reserves line
// buffers for its 8-million-pixel rows (under the sanitizers that took more than the fuzzer's 10 s).
TEST(Image, ExrHeaderIsReadWithoutOpeningTheImage) {
  test::TempDir dir;
  const auto bomb = exr_declared_layout(write_bomb(dir));
  ASSERT_TRUE(bomb.has_value());
  EXPECT_EQ(bomb->width, 7995408);
  EXPECT_EQ(bomb->height, 8);
  EXPECT_EQ(bomb->bytes_per_pixel, 12);
  EXPECT_EQ(bomb->chunk_bytes, 7995408.0 * 16 * 12);  // ZIP: 16 rows a chunk
  write_image(dir.file("a.exr"), Image(5, 3, 3, 1.0f));
  write_image(dir.file("a.png"), Image(5, 3, 3, 0.5f));
  const auto a = exr_declared_layout(dir.file("a.exr"));
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->width, 5);
  EXPECT_EQ(a->height, 3);
  EXPECT_FALSE(exr_declared_layout(dir.file("a.png")).has_value());
  EXPECT_FALSE(exr_declared_layout(dir.file("missing.exr")).has_value());
  // Channels of mixed types, and a tiled file's chunk is its tile whatever its data window.
  OIIO::ImageSpec mixed(7, 2, 3, OIIO::TypeDesc::FLOAT);
  mixed.channelformats = {OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::UINT};
  mixed.tile_width = 64;
  mixed.tile_height = 32;
  write_with_oiio(dir.file("mixed.exr"), mixed, std::vector<float>(7 * 2 * 3, 1.0f));
  const auto m = exr_declared_layout(dir.file("mixed.exr"));
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->bytes_per_pixel, 2 + 4 + 4);
  EXPECT_EQ(m->chunk_bytes, 64.0 * 32 * 10);
}

// The fuzzer's 64-megapixel bomb (its displayWindow's name mangled) and a one-bit mutant of it
// (lineOrder's): OpenEXR's C++ reader accepts a header without those required attributes and
// reserved what it declared (11 s under the sanitizers), while OpenEXRCore, lenient, read a
// different data window. A header OpenEXRCore's strict parse refuses is refused, naming the file.
TEST(Image, ExrHeaderCoreCannotParseIsRefused) {
  const auto expect_refused = [](const std::string& path, const std::function<void()>& read) {
    try {
      read();
      ADD_FAILURE() << path << " was read";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), path);
      EXPECT_EQ(e.message().rfind("cannot read the OpenEXR header: ", 0), 0u) << e.message();
    }
  };
  for (const char* name : {"exr_header_core_rejects.exr", "bomb_64_megapixels.exr"}) {
    const std::string path = test::test_data(name);
    expect_refused(path, [&] { read_image_file(path); });
    expect_refused(path, [&] { read_image_size(path); });
  }
}

// A header of 64 float channels (256 bytes a pixel) declaring 16.8 megapixels in a file of a few
// kilobytes: 4.3 GB decoded, refused as a bomb in bytes (in pixels it was at the old floor and
// passed to OpenEXR, which reserved its line buffers: the image fuzzer's timeout on 2026-11-23).
TEST(Image, ManyChannelBombIsRefusedInBytes) {
  test::TempDir dir;
  write_with_oiio(dir.file("c.exr"), OIIO::ImageSpec(16, 8, 64, OIIO::TypeDesc::FLOAT),
                  std::vector<float>(16 * 8 * 64, 0.5f));
  const std::string path = with_data_window(dir.file("c.exr"), 4096, 4096);
  ASSERT_FALSE(path.empty());
  try {
    read_image_file(path);
    FAIL() << "the bomb was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), path);
    EXPECT_NE(e.message().find("4096x4096 pixels of 256 bytes (4295 MB)"), std::string::npos) << e.what();
  }
}

// A chunk OpenEXR would reserve several times before the first pixel: 16384 pixels × 32 float
// channels × 256 rows (DWAB) is 537 MB although the image is one row of 2.1 MB. Refused; the same
// row uncompressed (one row a chunk) is read.
TEST(Image, ExrChunkAbove256MiBIsRefusedFromTheHeader) {
  test::TempDir dir;
  OIIO::ImageSpec spec(16384, 1, 32, OIIO::TypeDesc::FLOAT);
  const std::vector<float> row(std::size_t(16384) * 32, 0.25f);
  spec.attribute("compression", "dwab");
  write_with_oiio(dir.file("dwab.exr"), spec, row);
  try {
    read_image_file(dir.file("dwab.exr"));
    FAIL() << "the chunk was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("chunks of 537 MB (128 bytes per pixel)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_image_size(dir.file("dwab.exr")), InputError);
  spec.attribute("compression", "none");
  write_with_oiio(dir.file("none.exr"), spec, row);
  const Image img = read_image_file(dir.file("none.exr")).stored;
  EXPECT_EQ(img.width, 16384);
  EXPECT_EQ(img.data[3 * 16383 + 2], 0.25f);
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
