#include "core/output_paths.h"
#include "core/file_check.h"
#include "core/image.h"
#include "core/staged_writes.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <functional>
#include <type_traits>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>

#include "core/colour.h"
#include "core/error.h"
#include "core/exr_header.h"
#include "core/temp_files.h"
#include "core/text_file.h"

namespace insitu {
namespace fs = std::filesystem;
using namespace OIIO;

namespace {

// Holds what C libraries print to stderr while an image is read (libpng writes "libpng error: ..."
// itself before OpenImageIO reports the same failure): on failure it is dropped, since the one-line
// InputError carries the reader's message; otherwise it is written back unchanged. With
// INSITU_KEEP_STDERR set (scripts/sanitize-and-fuzz.sh) nothing is captured.
class StderrCapture {
 public:
  StderrCapture() {
    // The fuzz runs set it: a crash report written while stderr is captured would be lost.
    if (std::getenv("INSITU_KEEP_STDERR")) return;
    std::fflush(stderr);
    file_ = std::tmpfile();
    saved_ = file_ ? ::dup(STDERR_FILENO) : -1;
    if (saved_ >= 0) ::dup2(::fileno(file_), STDERR_FILENO);
  }
  ~StderrCapture() {
    if (saved_ < 0) {
      if (file_) std::fclose(file_);
      return;
    }
    std::fflush(stderr);
    ::dup2(saved_, STDERR_FILENO);
    ::close(saved_);
    if (!failed_) {
      std::rewind(file_);
      char buf[4096];
      for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, file_)) > 0;) std::fwrite(buf, 1, n, stderr);
    }
    std::fclose(file_);
  }
  void failed() { failed_ = true; }

 private:
  std::FILE* file_ = nullptr;
  int saved_ = -1;
  bool failed_ = false;
};

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s.empty() ? "unknown error" : s;
}

// Reads the image (from `bytes` when given, `path` then naming it and its format by its
// extension); read_image_file() wraps it in a StderrCapture. With `texels_as_bytes`, an 8-bit
// file's pixels go to ImageFile::stored_bytes and alpha_bytes.
ImageFile read_image_file_quietly(const std::string& path, PixelGrid grid, AlphaChannel alpha,
                                  const std::vector<unsigned char>* bytes = nullptr, bool texels_as_bytes = false);

// Runs read(), dropping what the C libraries printed if it fails (StderrCapture).
template <class Read>
ImageFile read_capturing_stderr(Read read) {
  StderrCapture capture;
  try {
    return read();
  } catch (...) {
    capture.failed();
    throw;
  }
}

}  // namespace

ImageFile read_image_file(const std::string& path, PixelGrid grid) {
  require_existing(path);
  return read_capturing_stderr([&] { return read_image_file_quietly(path, grid, AlphaChannel::kDrop); });
}

ImageFile read_image_memory(const std::string& name, const std::vector<unsigned char>& bytes, PixelGrid grid,
                            AlphaChannel alpha) {
  return read_capturing_stderr([&] { return read_image_file_quietly(name, grid, alpha, &bytes); });
}

ImageFile read_texture_file(const std::string& path, AlphaChannel alpha) {
  require_existing(path);
  return read_capturing_stderr(
      [&] { return read_image_file_quietly(path, PixelGrid::kAsStored, alpha, nullptr, true); });
}

ImageFile read_texture_memory(const std::string& name, const std::vector<unsigned char>& bytes, AlphaChannel alpha) {
  return read_capturing_stderr(
      [&] { return read_image_file_quietly(name, PixelGrid::kAsStored, alpha, &bytes, true); });
}

namespace {

// Reads the image's first three channels (one channel, repeated, for grey) as RGB of type T (float,
// or uint8_t for an 8-bit file's bytes), a band of rows at a time: memory grows only with rows that
// really decode, so a truncated file whose header declares 100 megapixels fails at its first
// missing band instead of after allocating and filling gigabytes (what the image fuzzer found).
// With `alpha`, also the alpha channel, where the header names one among the first four.
template <class T>
struct DecodedPixels {
  std::vector<T> rgb, alpha;
};

template <class T>
DecodedPixels<T> decode_pixels(ImageInput& in, const std::string& path, bool want_alpha) {
  const TypeDesc type = std::is_same_v<T, float> ? TypeDesc::FLOAT : TypeDesc::UINT8;
  const ImageSpec& spec = in.spec();
  const int colour_channels = spec.nchannels >= 3 ? 3 : 1;
  const int alpha_channel =
      want_alpha && spec.alpha_channel >= colour_channels && spec.alpha_channel < 4 ? spec.alpha_channel : -1;
  const int channels_read = std::max(colour_channels, alpha_channel + 1);
  const bool tiled = spec.tile_width > 0;
  const int tile_rows = std::max(1, spec.tile_height);
  const int band_rows = tiled ? tile_rows * std::max(1, 64 / tile_rows) : 64;
  const std::size_t row_values = std::size_t(spec.width) * channels_read;
  DecodedPixels<T> out;
  out.rgb.reserve(std::size_t(spec.width) * spec.height * 3);
  std::vector<T> band;
  if (alpha_channel >= 0) out.alpha.reserve(std::size_t(spec.width) * spec.height);
  for (int y0 = 0; y0 < spec.height; y0 += band_rows) {
    const int y1 = std::min(spec.height, y0 + band_rows);
    band.resize(row_values * std::size_t(y1 - y0));
    const bool ok =
        tiled ? in.read_tiles(0, 0, spec.x, spec.x + spec.width, spec.y + y0, spec.y + y1, spec.z, spec.z + 1, 0,
                              channels_read, type, band.data())
              : in.read_scanlines(0, 0, spec.y + y0, spec.y + y1, spec.z, 0, channels_read, type, band.data());
    if (!ok) throw InputError(path, "cannot decode image: " + one_line(in.geterror()));
    // A truncated file may decode "successfully" with its missing rows grey: the reader's error
    // says so.
    if (in.has_error()) throw InputError(path, "truncated or corrupt image: " + one_line(in.geterror()));
    const std::size_t first = out.rgb.size();
    out.rgb.resize(first + band.size() / channels_read * 3);
    for (std::size_t i = 0, o = first; i < band.size(); i += channels_read, o += 3) {
      for (int c = 0; c < 3; ++c) out.rgb[o + c] = band[i + (colour_channels == 3 ? c : 0)];
      if (alpha_channel >= 0) out.alpha.push_back(band[i + std::size_t(alpha_channel)]);
    }
  }
  return out;
}

template <class Pixels, class T>
Pixels pixels_of(const ImageSpec& spec, int channels, std::vector<T> data) {
  Pixels p;
  p.width = spec.width, p.height = spec.height, p.channels = channels;
  p.data = std::move(data);
  return p;
}

// The image's RGB as floats, and its alpha into *alpha where asked for and present.
Image decode_rgb(ImageInput& in, const std::string& path, Image* alpha = nullptr) {
  DecodedPixels<float> d = decode_pixels<float>(in, path, alpha != nullptr);
  if (!d.alpha.empty()) *alpha = pixels_of<Image>(in.spec(), 1, std::move(d.alpha));
  return pixels_of<Image>(in.spec(), 3, std::move(d.rgb));
}

// The same as bytes, for an 8-bit file.
ByteImage decode_rgb_bytes(ImageInput& in, const std::string& path, ByteImage* alpha = nullptr) {
  DecodedPixels<std::uint8_t> d = decode_pixels<std::uint8_t>(in, path, alpha != nullptr);
  if (!d.alpha.empty()) *alpha = pixels_of<ByteImage>(in.spec(), 1, std::move(d.alpha));
  return pixels_of<ByteImage>(in.spec(), 3, std::move(d.rgb));
}

// The header's size is checked before anything is allocated: a 100000² header, or a header of a
// thousand channels, must not cost memory or minutes.
void check_declared_size(const std::string& path, std::int64_t width, std::int64_t height,
                         std::int64_t bytes_per_pixel) {
  if (width <= 0 || height <= 0) return;
  const double pixels = double(width) * double(height);
  if (pixels > double(kMaxImagePixels))
    throw InputError(path, fmt::format("the header declares {}x{} pixels, more than the {} megapixels insitu reads",
                                       width, height, kMaxImagePixels / 1000000));
  const double decoded_bytes = pixels * double(bytes_per_pixel);
  std::error_code ec;
  const double bytes = double(std::filesystem::file_size(path, ec));
  if (!ec && decoded_bytes > double(kBombFloorBytes) && decoded_bytes > double(kMaxDecodedBytesPerByte) * bytes)
    throw InputError(path,
                     fmt::format("the header declares {}x{} pixels of {} bytes ({:.0f} MB) in a file of {} bytes: "
                                 "too compressed to be a photo or an environment (a decompression bomb?)",
                                 width, height, bytes_per_pixel, decoded_bytes / 1e6, bytes));
}

// An EXR's header is read before OpenEXR's reader allocates its line buffers (exr_header.h).
void check_exr_header(const std::string& path) {
  const auto exr = exr_declared_layout(path);
  if (!exr) return;
  check_declared_size(path, exr->width, exr->height, exr->bytes_per_pixel);
  if (exr->chunk_bytes > kMaxChunkBytes)
    throw InputError(path,
                     fmt::format("the header declares chunks of {:.0f} MB ({} bytes per pixel), more than the {} MB "
                                 "insitu reads (OpenEXR reserves several before the first pixel)",
                                 exr->chunk_bytes / 1e6, exr->bytes_per_pixel, std::uint64_t(kMaxChunkBytes) >> 20));
}

// Integer pixels are display-referred (encoded for a screen); float ones are radiance.
bool display_referred(const ImageSpec& spec) {
  const TypeDesc::BASETYPE t = TypeDesc::BASETYPE(spec.format.basetype);
  return !(t == TypeDesc::FLOAT || t == TypeDesc::HALF || t == TypeDesc::DOUBLE);
}

// EXIF orientation 1–8 (TIFF 6.0, tag 274): 5–8 swap width and height. Others are ignored (1).
int exif_orientation(const ImageSpec& spec) {
  const int o = spec.get_int_attribute("Orientation", 1);
  return o >= 1 && o <= 8 ? o : 1;
}

// The image as displayed: turned and mirrored as the tag says, by OpenImageIO's exact pixel
// moves. Not ImageBufAlgo::reorient: before OpenImageIO 2.5.x/3.x (PR #5350; Debian 12 has 2.4.7)
// it swaps 5 and 7, transverse for transpose (issue #4661), which the test of every tag caught.
ImageBuf shown_as_tagged(const ImageBuf& stored, int orientation) {
  switch (orientation) {
    case 2:
      return ImageBufAlgo::flop(stored);  // mirrored left–right
    case 3:
      return ImageBufAlgo::rotate180(stored);
    case 4:
      return ImageBufAlgo::flip(stored);  // mirrored top–bottom
    case 5:
      return ImageBufAlgo::transpose(stored);  // row 0 left, column 0 top
    case 6:
      return ImageBufAlgo::rotate90(stored);  // clockwise
    case 7:
      return ImageBufAlgo::rotate180(ImageBufAlgo::transpose(stored));  // transverse
    case 8:
      return ImageBufAlgo::rotate270(stored);  // anticlockwise
    default:
      return ImageBufAlgo::copy(stored);
  }
}

Image reoriented(Image img, int orientation, const std::string& path) {
  if (orientation == 1) return img;
  const ImageBuf stored(ImageSpec(img.width, img.height, 3, TypeDesc::FLOAT), img.data.data());  // wraps, no copy
  const ImageBuf shown = shown_as_tagged(stored, orientation);
  Image out(shown.spec().width, shown.spec().height, 3);
  if (shown.has_error() || !shown.get_pixels(shown.roi(), TypeDesc::FLOAT, out.data.data()))
    throw InputError(path, "cannot turn the image as its EXIF orientation says: " + one_line(shown.geterror()));
  return out;
}

ImageFile read_image_file_quietly(const std::string& path, PixelGrid grid, AlphaChannel alpha,
                                  const std::vector<unsigned char>* bytes, bool texels_as_bytes) {
  std::optional<Filesystem::IOMemReader> memory;
  if (bytes) {
    const auto ext = fs::path(path).extension();
    if (ext != ".png" && ext != ".jpg") throw InputError(path, "an embedded image must be a PNG or a JPEG");
    memory.emplace(bytes->data(), bytes->size());
  } else {
    check_exr_header(path);
  }
  // Colour as stored: OpenImageIO would otherwise premultiply a PNG's colour by its alpha, where
  // glTF, OBJ viewers and Blender read it straight.
  ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  Filesystem::IOProxy* proxy = memory ? &*memory : nullptr;
  if (proxy) config.attribute("oiio:ioproxy", TypeDesc::PTR, &proxy);  // with a config, read from there
  auto in = ImageInput::open(path, &config, proxy);
  if (!in) throw InputError(path, "cannot read image: " + one_line(geterror()));
  const ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) throw InputError(path, "image has no pixels");
  if (spec.depth > 1)
    throw InputError(path, fmt::format("a volume image ({} slices); insitu reads flat images", spec.depth));
  check_declared_size(path, spec.width, spec.height, std::int64_t(spec.pixel_bytes(true)));
  ImageFile file;
  file.path = path;
  file.format = in->format_name();
  file.display_referred = display_referred(spec);
  file.bits = int(spec.format.size()) * 8;
  if (const float t = spec.get_float_attribute("ExposureTime", 0.0f); t > 0) file.exposure.time_s = t;
  if (const float n = spec.get_float_attribute("FNumber", 0.0f); n > 0) file.exposure.f_number = n;
  int iso = spec.get_int_attribute("Exif:PhotographicSensitivity", 0);
  if (iso <= 0) iso = spec.get_int_attribute("Exif:ISOSpeedRatings", 0);
  if (iso > 0) file.exposure.iso = iso;
  if (const int f35 = spec.get_int_attribute("Exif:FocalLengthIn35mmFilm", 0); f35 > 0)
    file.exposure.focal_35mm_mm = f35;
  file.orientation = grid == PixelGrid::kAsDisplayed ? exif_orientation(spec) : 1;
  const bool keep_alpha = alpha == AlphaChannel::kKeep && grid == PixelGrid::kAsStored;
  if (texels_as_bytes && spec.format.basetype == TypeDesc::UINT8)  // as stored: no orientation to apply
    file.stored_bytes = decode_rgb_bytes(*in, path, keep_alpha ? &file.alpha_bytes : nullptr);
  else
    file.stored = reoriented(decode_rgb(*in, path, keep_alpha ? &file.alpha : nullptr), file.orientation, path);
  in->close();
  return file;
}

}  // namespace

Rgb bilinear_rgb(const Image& img, double x, double y) {
  const int x0 = std::min(int(x), img.width - 1), y0 = std::min(int(y), img.height - 1);
  const int x1 = std::min(x0 + 1, img.width - 1), y1 = std::min(y0 + 1, img.height - 1);
  const float wx = float(x - x0), wy = float(y - y0);
  return (1 - wy) * ((1 - wx) * img.rgb(x0, y0) + wx * img.rgb(x1, y0)) +
         wy * ((1 - wx) * img.rgb(x0, y1) + wx * img.rgb(x1, y1));
}

std::optional<double> Exposure::relative() const {
  if (!time_s) return std::nullopt;
  const double n = f_number.value_or(1.0);
  return *time_s * iso.value_or(1.0) / (n * n);
}

ImageHeader read_image_header(const std::string& path) {
  require_existing(path);
  check_exr_header(path);
  auto in = ImageInput::open(path);
  if (!in) throw InputError(path, "cannot read image: " + geterror());
  const ImageSpec& spec = in->spec();
  ImageHeader h{spec.width, spec.height, display_referred(spec), int(spec.format.size()) * 8};
  if (exif_orientation(spec) >= 5) std::swap(h.width, h.height);
  return h;
}

std::pair<int, int> read_image_size(const std::string& path) {
  const ImageHeader h = read_image_header(path);
  return {h.width, h.height};
}

std::size_t sanitize(Image& img) {
  std::size_t count = 0;
  for (float& v : img.data)
    if (!(v >= 0.0f) || !std::isfinite(v)) {
      v = 0.0f;
      ++count;
    }
  return count;
}

Image linearize(const ImageFile& file, std::size_t* clamped) {
  Image img = file.stored;
  std::size_t count = sanitize(img);
  if (file.display_referred)
    for (float& v : img.data) v = srgb_to_linear(v);
  if (clamped) *clamped = count;
  return img;
}

namespace {

// "dir/name.ext" -> "dir/.name.tmp-<pid>-<n>.ext": same folder (so rename is atomic), same
// extension (so OpenImageIO picks the same format).
std::string temporary_name(const fs::path& final_path) {
  static std::atomic<int> counter{0};
  return (final_path.parent_path() / fmt::format(".{}.tmp-{}-{}{}", final_path.stem().string(), ::getpid(), counter++,
                                                 final_path.extension().string()))
      .string();
}

void commit(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    const std::string why = is_directory_quietly(path) ? "is a directory" : "cannot write: " + ec.message();
    std::error_code ignored;  // the removal's own outcome must not replace the reason
    fs::remove(tmp, ignored);
    throw InputError(path, why);
  }
}

void make_parent(const fs::path& p) {
  std::error_code ec;
  if (!p.parent_path().empty()) fs::create_directories(p.parent_path(), ec);
  if (ec) throw InputError(p.string(), "cannot create folder: " + ec.message());
}

TypeDesc storage_type(const std::string& ext_lower) {
  // Float, not half, for EXR: radiance spans 1e-6 to 1e5 and half overflows at 65504.
  if (ext_lower == ".exr" || ext_lower == ".hdr" || ext_lower == ".pfm" || ext_lower == ".tif" || ext_lower == ".tiff")
    return TypeDesc::FLOAT;
  return TypeDesc::UINT8;
}

// Reads a written image back to its last row, in bands (bounded memory at any size): "" when it
// decodes whole with the shape written, else why not. For the formats whose library writes the
// file itself (EXR, TIFF, HDR; PNG and JPEG go through memory, write_through_memory): OpenImageIO's
// writers do not all report short writes (its PNG writer returned success for a file cut short
// by a full disk), and a file that reads back whole was written whole.
std::string read_back_failure(const std::string& path, const ImageSpec& spec) {
  StderrCapture capture;  // libpng prints its own "libpng error" before OpenImageIO reports it
  auto in = ImageInput::open(path);
  if (!in) {
    capture.failed();
    return "the file written does not open again (a full disk?): " + one_line(OIIO::geterror());
  }
  const ImageSpec& got = in->spec();
  if (got.width != spec.width || got.height != spec.height || got.nchannels != spec.nchannels) {
    capture.failed();
    return fmt::format("the file written reads back as {}x{}x{}, not {}x{}x{}", got.width, got.height, got.nchannels,
                       spec.width, spec.height, spec.nchannels);
  }
  constexpr int kBandRows = 64;
  std::vector<float> band(std::size_t(spec.width) * std::size_t(spec.nchannels) * kBandRows);
  for (int y = 0; y < spec.height; y += kBandRows)
    if (!in->read_scanlines(0, 0, y, std::min(spec.height, y + kBandRows), 0, 0, spec.nchannels, TypeDesc::FLOAT,
                            band.data())) {
      capture.failed();
      return "the file written is cut short or damaged (a full disk?): " + one_line(in->geterror());
    }
  return "";
}

// An 8-bit image (PNG, JPEG: a few MB at most) is encoded in memory, then written as bytes by
// write_binary_file, whose every write and fsync is checked. libjpeg, writing a file itself, ends
// the process on a full disk (exit 1, its own message, a temporary file left behind).
void write_through_memory(const std::string& path, const ImageSpec& spec, ImageOutput& out,
                          const std::function<bool(ImageOutput&)>& write_pixels, StagedWrites* stage) {
  std::vector<unsigned char> bytes;
  Filesystem::IOVecOutput memory(bytes);
  if (!out.set_ioproxy(&memory) || !out.open(path, spec) || !write_pixels(out) || !out.close())
    throw InputError(path, "cannot write image: " + one_line(out.geterror()));
  write_binary_file(path, std::string(bytes.begin(), bytes.end()), stage);
}

// Writes an image with `spec` under a temporary name, flushes it to the disk, reads it back whole,
// then renames it to `path` (or stages it: core/staged_writes.h); `write_pixels` writes the pixels
// through the open output (false: failed, with its error). On any failure the temporary file is
// removed and an InputError names `path`: no image that does not open ever gets its final name.
void write_atomically(const std::string& path, const std::string& format, const ImageSpec& spec,
                      const std::function<bool(ImageOutput&)>& write_pixels, StagedWrites* stage) {
  const fs::path p(path);
  make_parent(p);
  // An image's temporaries are named by its stem (temporary_name); write_binary_file, which
  // writes the PNG and JPEG encoded in memory, removes those named by the whole file name.
  remove_stale_temporaries(path, p.stem().string());
  const std::string tmp = temporary_name(p);
  auto out = ImageOutput::create(format.empty() ? tmp : format);
  if (!out) throw InputError(path, "no image format for '" + p.extension().string() + "'");
  if (spec.format == TypeDesc::UINT8 && out->supports("ioproxy"))
    return write_through_memory(path, spec, *out, write_pixels, stage);
  const TempFileGuard guard(tmp);  // removed if the process is interrupted meanwhile
  std::string err;
  if (!out->open(tmp, spec) || !write_pixels(*out) || !out->close()) err = out->geterror();
  out.reset();
  if (err.empty()) err = sync_to_disk(tmp);
  if (err.empty()) err = read_back_failure(tmp, spec);
  if (!err.empty()) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw InputError(path, "cannot write image: " + err);
  }
  if (stage)
    stage->add(tmp, path);
  else
    commit(tmp, path);
}

}  // namespace

void write_image(const std::string& path, const Image& img, const Exposure* exposure, StagedWrites* stage) {
  const std::string ext = lower_extension(path);
  ImageSpec spec(img.width, img.height, img.channels, storage_type(ext));
  if (ext == ".jpg" || ext == ".jpeg") spec.attribute("CompressionQuality", 92);
  if (exposure) {
    if (exposure->time_s) spec.attribute("ExposureTime", float(*exposure->time_s));
    if (exposure->f_number) spec.attribute("FNumber", float(*exposure->f_number));
    if (exposure->iso) spec.attribute("Exif:PhotographicSensitivity", int(*exposure->iso));
    if (exposure->focal_35mm_mm) spec.attribute("Exif:FocalLengthIn35mmFilm", int(*exposure->focal_35mm_mm));
  }
  write_atomically(
      path, "", spec, [&](ImageOutput& out) { return out.write_image(TypeDesc::FLOAT, img.data.data()); }, stage);
}

void write_exr_channels(const std::string& path, int width, int height, const std::vector<ExrChannel>& channels,
                        bool half_float, StagedWrites* stage) {
  const int nc = int(channels.size());
  ImageSpec spec(width, height, nc, half_float ? TypeDesc::HALF : TypeDesc::FLOAT);
  spec.channelnames.clear();
  for (const auto& ch : channels) spec.channelnames.push_back(ch.name);
  spec.alpha_channel = -1;
  for (int i = 0; i < nc; ++i)
    if (channels[i].name == "A") spec.alpha_channel = i;
  spec.attribute("compression", "zip");
  // Interleaved and written 256 rows at a time (16 of zip's 16-row chunks, compressed in parallel
  // by OpenEXR): the whole image interleaved at once was another copy of every channel.
  constexpr int kRows = 256;
  std::vector<float> block(std::size_t(width) * std::size_t(std::min(height, kRows)) * std::size_t(nc));
  write_atomically(
      path, "openexr", spec,
      [&](ImageOutput& out) {
        for (int y0 = 0; y0 < height; y0 += kRows) {
          const int y1 = std::min(height, y0 + kRows);
          const std::size_t first = std::size_t(y0) * std::size_t(width),
                            count = std::size_t(y1 - y0) * std::size_t(width);
          for (int i = 0; i < nc; ++i) {
            const Image& src = *channels[i].image;
            for (std::size_t k = 0; k < count; ++k)
              block[k * std::size_t(nc) + std::size_t(i)] =
                  src.data[(first + k) * std::size_t(src.channels) + std::size_t(channels[i].channel)];
          }
          if (!out.write_scanlines(y0, y1, 0, TypeDesc::FLOAT, block.data())) return false;
        }
        return true;
      },
      stage);
}

Image resize(const Image& img, int width, int height, const std::string& filter) {
  ImageSpec spec(img.width, img.height, img.channels, TypeDesc::FLOAT);
  ImageBuf src(spec, const_cast<float*>(img.data.data()));
  ImageSpec dst_spec(width, height, img.channels, TypeDesc::FLOAT);
  ImageBuf dst(dst_spec);
  if (!ImageBufAlgo::resize(dst, src, filter)) throw std::runtime_error("resize: " + dst.geterror());
  Image out(width, height, img.channels);
  dst.get_pixels(ROI::All(), TypeDesc::FLOAT, out.data.data());
  return out;
}

Image rotated_clockwise(const Image& img, int deg) {
  assert(deg == 0 || deg == 90 || deg == 180 || deg == 270);
  if (deg == 0) return img;
  ImageSpec spec(img.width, img.height, img.channels, TypeDesc::FLOAT);
  ImageBuf src(spec, const_cast<float*>(img.data.data()));
  ImageBuf dst;
  const bool ok = deg == 90    ? ImageBufAlgo::rotate90(dst, src)
                  : deg == 180 ? ImageBufAlgo::rotate180(dst, src)
                               : ImageBufAlgo::rotate270(dst, src);
  if (!ok) throw std::runtime_error("rotate: " + dst.geterror());
  const bool swap = deg != 180;
  Image out(swap ? img.height : img.width, swap ? img.width : img.height, img.channels);
  dst.get_pixels(ROI::All(), TypeDesc::FLOAT, out.data.data());
  return out;
}

}  // namespace insitu
