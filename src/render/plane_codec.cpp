#include "render/plane_codec.h"

#include <stdexcept>
#include <zstd.h>

#include "core/error.h"

namespace insitu {
namespace {

// zstd's level 3 (its default): 0.5 s a 1920×1440 part on one core; higher levels gain 3 %.
constexpr int kLevel = 3;
// The most a zstd frame can hold per byte of it: a block holds at most 128 KiB and costs at least
// 4 bytes (an RLE block: a 3-byte header and its byte; RFC 8878, 3.1.1.2), so a frame that
// declares more than 32768 times its size is not one, whatever its header says.
constexpr std::uint64_t kMaxExpansion = (std::uint64_t(128) << 10) / 4;
// The largest window a frame may ask for (2^23 = 8 MB): what level 3 uses (2^21) with room.
constexpr int kWindowLogMax = 23;

std::vector<std::uint8_t> shuffle(const std::vector<std::uint32_t>& words) {
  const std::size_t n = words.size();
  std::vector<std::uint8_t> out(4 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int b = 0; b < 4; ++b) out[std::size_t(b) * n + i] = std::uint8_t(words[i] >> (8 * b));
  return out;
}

std::vector<std::uint32_t> unshuffle(const std::vector<std::uint8_t>& bytes) {
  const std::size_t n = bytes.size() / 4;
  std::vector<std::uint32_t> out(n, 0);
  for (int b = 0; b < 4; ++b)
    for (std::size_t i = 0; i < n; ++i) out[i] |= std::uint32_t(bytes[std::size_t(b) * n + i]) << (8 * b);
  return out;
}

}  // namespace

struct PlaneWriter::Stream {
  ZSTD_CCtx* ctx = ZSTD_createCCtx();
  std::uint64_t pledged = 0, fed = 0;
  ~Stream() { ZSTD_freeCCtx(ctx); }
};

PlaneWriter::PlaneWriter(std::uint64_t content_bytes) : z_(std::make_unique<Stream>()) {
  if (z_->ctx == nullptr) throw std::bad_alloc();
  z_->pledged = content_bytes;
  ZSTD_CCtx_setParameter(z_->ctx, ZSTD_c_compressionLevel, kLevel);
  ZSTD_CCtx_setPledgedSrcSize(z_->ctx, content_bytes);  // the frame declares its size
}

PlaneWriter::~PlaneWriter() = default;

void PlaneWriter::feed(const void* data, std::size_t n) {
  ZSTD_inBuffer in{data, n, 0};
  std::string chunk(ZSTD_CStreamOutSize(), '\0');
  while (in.pos < in.size) {
    ZSTD_outBuffer out{chunk.data(), chunk.size(), 0};
    const std::size_t r = ZSTD_compressStream2(z_->ctx, &out, &in, ZSTD_e_continue);
    if (ZSTD_isError(r)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(r));
    frame_.append(chunk.data(), out.pos);
  }
  z_->fed += n;
}

void PlaneWriter::words(const std::vector<std::uint32_t>& plane) {
  const std::vector<std::uint8_t> b = shuffle(plane);
  feed(b.data(), b.size());
}

void PlaneWriter::bytes(const std::uint8_t* data, std::size_t n) { feed(data, n); }

std::string PlaneWriter::finish() {
  if (z_->fed != z_->pledged) throw std::logic_error("PlaneWriter: planes of another size than pledged");
  std::string chunk(ZSTD_CStreamOutSize(), '\0');
  ZSTD_inBuffer in{nullptr, 0, 0};
  for (std::size_t left = 1; left != 0;) {
    ZSTD_outBuffer out{chunk.data(), chunk.size(), 0};
    left = ZSTD_compressStream2(z_->ctx, &out, &in, ZSTD_e_end);
    if (ZSTD_isError(left)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(left));
    frame_.append(chunk.data(), out.pos);
  }
  return std::move(frame_);
}

struct PlaneReader::Stream {
  ZSTD_DCtx* ctx = ZSTD_createDCtx();
  ZSTD_inBuffer in{nullptr, 0, 0};
  std::size_t last = 1;  // ZSTD_decompressStream's last answer: 0 once the frame ended
  ~Stream() { ZSTD_freeDCtx(ctx); }
};

PlaneReader::PlaneReader(const char* frame, std::size_t frame_bytes, std::uint64_t content_bytes, std::string path)
    : z_(std::make_unique<Stream>()), path_(std::move(path)) {
  if (z_->ctx == nullptr) throw std::bad_alloc();
  if (content_bytes > kMaxExpansion * frame_bytes + 64 || ZSTD_getFrameContentSize(frame, frame_bytes) != content_bytes)
    throw InputError(path_, "damaged pixel data (a frame of another size than its header implies)");
  ZSTD_DCtx_setParameter(z_->ctx, ZSTD_d_windowLogMax, kWindowLogMax);
  z_->in = {frame, frame_bytes, 0};
}

PlaneReader::~PlaneReader() = default;

// A call that neither reads nor writes a byte means the frame has no more to give.
void PlaneReader::take(void* data, std::size_t n) {
  ZSTD_outBuffer out{data, n, 0};
  while (out.pos < out.size) {
    if (z_->last == 0) throw InputError(path_, "truncated pixel data");
    const std::size_t in_before = z_->in.pos, out_before = out.pos;
    z_->last = ZSTD_decompressStream(z_->ctx, &out, &z_->in);
    if (ZSTD_isError(z_->last))
      throw InputError(path_, std::string("damaged pixel data (zstd: ") + ZSTD_getErrorName(z_->last) + ")");
    if (z_->in.pos == in_before && out.pos == out_before) throw InputError(path_, "truncated pixel data");
  }
}

std::vector<std::uint32_t> PlaneReader::words(std::size_t n) {
  std::vector<std::uint8_t> b(4 * n);
  take(b.data(), b.size());
  return unshuffle(b);
}

void PlaneReader::bytes(std::uint8_t* out, std::size_t n) { take(out, n); }

// The frame's epilogue: what is left must decode to nothing and end the frame.
void PlaneReader::finish() {
  char extra = 0;
  while (z_->last != 0) {
    ZSTD_outBuffer out{&extra, 1, 0};
    const std::size_t in_before = z_->in.pos;
    z_->last = ZSTD_decompressStream(z_->ctx, &out, &z_->in);
    if (ZSTD_isError(z_->last) || out.pos != 0 || (z_->in.pos == in_before && z_->last != 0))
      throw InputError(path_, "damaged pixel data (its frame does not end where its header implies)");
  }
  if (z_->in.pos != z_->in.size) throw InputError(path_, "damaged pixel data (bytes after its frame)");
}

}  // namespace insitu
