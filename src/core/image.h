// Float images and their file I/O through OpenImageIO. Writes are atomic: the file is written
// under a temporary name in the same folder and renamed, so no half-written output ever carries
// the final name (DESIGN.md "Errors").
#pragma once
#include <cstdint>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"

namespace insitu {

class StagedWrites;  // core/staged_writes.h

struct Image {
  int width = 0, height = 0, channels = 0;
  std::vector<float> data;  // row-major, row 0 at the top, channels interleaved

  Image() = default;
  Image(int w, int h, int c, float fill = 0.0f)
      : width(w), height(h), channels(c), data(std::size_t(w) * h * c, fill) {}
  bool empty() const { return data.empty(); }
  float* at(int x, int y) { return &data[(std::size_t(y) * width + x) * channels]; }
  const float* at(int x, int y) const { return &data[(std::size_t(y) * width + x) * channels]; }
  Rgb rgb(int x, int y) const {
    const float* p = at(x, y);
    return {p[0], p[1], p[2]};
  }
  void set_rgb(int x, int y, const Rgb& c) {
    float* p = at(x, y);
    p[0] = c[0];
    p[1] = c[1];
    p[2] = c[2];
  }
};

// The bilinear interpolation of img's RGB at (x, y) in pixel indices (pixel (i, j)'s centre at
// x = i, y = j), for 0 ≤ x ≤ width − 1 and 0 ≤ y ≤ height − 1; the far edge's neighbour is itself.
Rgb bilinear_rgb(const Image& img, double x, double y);

// 8-bit pixels as a file stores them (value k means k/255): a texture's, a quarter of the memory
// of floats. Row-major, row 0 at the top, channels interleaved.
struct ByteImage {
  int width = 0, height = 0, channels = 0;
  std::vector<std::uint8_t> data;

  bool empty() const { return data.empty(); }
  const std::uint8_t* at(int x, int y) const { return &data[(std::size_t(y) * width + x) * channels]; }
};

// What a camera recorded about an exposure (EXIF, through OpenImageIO); absent values are empty.
struct Exposure {
  std::optional<double> time_s, f_number, iso, focal_35mm_mm;
  // The relative exposure k = t · ISO / N² (missing ISO or N count as 1: taken as equal between
  // the images compared). Empty without an exposure time.
  std::optional<double> relative() const;
};

// An image file: its values as stored, normalized by OpenImageIO (8-bit k -> k/255), always RGB,
// its pixels as displayed (the EXIF orientation applied).
struct ImageFile {
  std::string path;
  Image stored;
  bool display_referred = false;  // integer pixels (8/16-bit): sRGB-encoded, decoded to linear
  std::string format;             // "png", "jpeg", "openexr", ...
  int bits = 32;                  // bits per stored channel
  Exposure exposure;
  // The EXIF orientation tag (1–8) that was applied: `stored` is the image as displayed, turned
  // and mirrored as a phone that writes the tag instead of turning its pixels means it. 1: none,
  // or read as stored (PixelGrid::kAsStored).
  int orientation = 1;
  // The file's alpha channel (one channel, as stored), where it was asked for (AlphaChannel::kKeep)
  // and the file has one; else empty.
  Image alpha;
  // Read as a texture (read_texture_file, read_texture_memory) from an 8-bit file: its pixels and
  // alpha as bytes, in place of `stored` and `alpha`, which stay empty.
  ByteImage stored_bytes, alpha_bytes;
};

// Images larger than this are refused from their header, before decoding (a 16384 × 8192 HDRI is
// 134 megapixels; phone photos are 12–50).
constexpr std::uint64_t kMaxImagePixels = std::uint64_t(1) << 27;
// A decompression bomb: more than 64 MiB decoded (all channels as stored), and more than 4096
// decoded bytes per byte of file. Real images stay far below 1000 (an 8-bit JPEG of a plain wall
// holds ~100 pixels per byte; zlib cannot pass 1032:1), while a constant EXR of 64 megapixels
// fits in 678 bytes (found by the image fuzzer), and one of 16 megapixels × 64 float channels in
// as little. Refused from the header too. (Counted in bytes, not pixels, since 2026-11-24: in
// pixels, a header's thousand channels went unchecked.)
constexpr std::uint64_t kBombFloorBytes = std::uint64_t(1) << 26;
constexpr std::uint64_t kMaxDecodedBytesPerByte = 4096;
// OpenEXR sizes its line buffers by the header's chunk (a row of all channels × up to 256 rows,
// or a tile), several of them, before the first pixel: a chunk above 256 MiB is refused from the
// header (a 16384-wide RGBA half image in 256-row DWAB chunks needs 32 MiB).
constexpr double kMaxChunkBytes = double(std::uint64_t(1) << 28);

// Photos and shots are read as displayed (the EXIF orientation applied: ImageFile::orientation);
// textures as stored, since UVs address the stored grid (as Blender and OBJ viewers read them).
enum class PixelGrid { kAsDisplayed, kAsStored };

// Refuses (InputError naming the file) a missing, unreadable, oversized, truncated or corrupt image.
ImageFile read_image_file(const std::string& path, PixelGrid grid = PixelGrid::kAsDisplayed);
// The same for an image held in memory (a glTF's embedded PNG or JPEG): `name` ends in ".png" or
// ".jpg", which chooses the decoder, and names the image in errors. kKeep also reads the alpha
// channel into ImageFile::alpha (a texture's opacity; with PixelGrid::kAsStored only).
enum class AlphaChannel { kDrop, kKeep };
ImageFile read_image_memory(const std::string& name, const std::vector<unsigned char>& bytes,
                            PixelGrid grid = PixelGrid::kAsDisplayed, AlphaChannel alpha = AlphaChannel::kDrop);
// A texture's image, read as stored (PixelGrid::kAsStored) and refused as above: an 8-bit file keeps
// its bytes (ImageFile::stored_bytes and alpha_bytes), which decode in about half the time and a
// quarter of the memory of floats; 16-bit and float files are read as floats.
ImageFile read_texture_file(const std::string& path, AlphaChannel alpha = AlphaChannel::kDrop);
ImageFile read_texture_memory(const std::string& name, const std::vector<unsigned char>& bytes,
                              AlphaChannel alpha = AlphaChannel::kDrop);
// What the header alone tells: the size as displayed (after the EXIF orientation), and whether the
// file is display-referred (integer pixels of `bits`) or scene-referred (float: an HDR image).
struct ImageHeader {
  int width = 0, height = 0;
  bool display_referred = false;
  int bits = 0;
};
ImageHeader read_image_header(const std::string& path);
// read_image_header's width and height.
std::pair<int, int> read_image_size(const std::string& path);

// Linear Rec.709: display-referred files through the inverse sRGB transfer function, float files
// as they are. Negative and non-finite values are clamped to 0 and counted in *clamped.
Image linearize(const ImageFile& file, std::size_t* clamped = nullptr);

// Clamps negative and non-finite values to 0; returns how many values it changed.
std::size_t sanitize(Image& img);

// Writes RGB(A) float pixels; the format follows the extension. 8-bit formats get the values
// rounded to k/255 after clamping to [0,1] (the caller encodes with sRGB first).
// `exposure`, when given, is written as EXIF (ExposureTime, FNumber, ISO, 35 mm focal length).
// With `stage`, the verified file waits under its temporary name for stage->commit()
// (core/staged_writes.h); without, it is renamed at once.
void write_image(const std::string& path, const Image& img, const Exposure* exposure = nullptr,
                 StagedWrites* stage = nullptr);

// A multi-part EXR written as one file: named channel groups ("R","G","B","A",
// "objects.R", ...), all of width x height, stored as half or float.
struct ExrChannel {
  std::string name;
  const Image* image;  // the source image
  int channel;         // which of its channels
};
void write_exr_channels(const std::string& path, int width, int height, const std::vector<ExrChannel>& channels,
                        bool half_float = false, StagedWrites* stage = nullptr);

// Resampling with a proper filter (OpenImageIO's ImageBufAlgo::resize); filter "" is OpenImageIO's
// default (Blackman-Harris), "box" the area average (keeps a radiance map's integral).
Image resize(const Image& img, int width, int height, const std::string& filter = "");
// The image turned clockwise (as displayed) by 0, 90, 180 or 270 degrees (OpenImageIO's
// ImageBufAlgo::rotate90/180/270); other angles are a programming error.
Image rotated_clockwise(const Image& img, int deg);

}  // namespace insitu
