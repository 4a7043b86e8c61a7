#include "render/checkpoint.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "core/float_bits.h"
#include "core/fnv1a.h"
#include "core/image.h"
#include "core/file_check.h"
#include "core/text_file.h"
#include "render/pixel_blocks.h"
#include "render/plane_codec.h"
#include "render/pixel_variance.h"

namespace insitu {
namespace {

constexpr char kMagic[8] = {'I', 'N', 'S', 'I', 'T', 'U', 'C', 'K'};
constexpr std::uint32_t kVersion = 8;

template <class T>
void put(std::string& out, T v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

template <class T>
T get(const std::string& in, std::size_t& at, const std::string& path) {
  if (in.size() - at < sizeof(T)) throw InputError(path, "truncated checkpoint");
  T v;
  std::memcpy(&v, in.data() + at, sizeof(T));
  at += sizeof(T);
  return v;
}

// A block as 24 words (Eigen's types are not trivially copyable): its RGB sums, albedo, normal,
// coverage, depth and 5 centred moments as float32 bits, then met and catcher. The sums without
// the objects and two of the moments are stored XOR the ones they mostly equal (a pixel the
// objects do not change has the same sums with and without them), so that equal bits are zeros.
// A block's samples follow from its pixel's (canonical_sizes), its batches and batch_y from them.
constexpr int kBlockWords = 24;
constexpr std::uint32_t kBlockBytes = 4 * kBlockWords;
// Blocks are written kChunkBlocks at a time, each chunk as 24 planes (render/plane_codec.h), so
// that neither side holds more than one chunk's words beside the state.
constexpr std::size_t kChunkBlocks = std::size_t(1) << 16;

void block_words(const PixelSums& p, std::uint32_t* w) {
  for (int k = 0; k < 3; ++k) {
    w[k] = float_bits(p.objects[k]), w[3 + k] = float_bits(p.with[k]), w[6 + k] = float_bits(p.without[k]) ^ w[3 + k];
    w[9 + k] = float_bits(p.albedo[k]), w[12 + k] = float_bits(p.normal[k]);
  }
  w[15] = float_bits(p.coverage), w[16] = float_bits(p.depth), w[17] = float_bits(p.m_yy), w[18] = float_bits(p.m_ww);
  w[19] = float_bits(p.m_nn) ^ w[18], w[20] = float_bits(p.m_wn) ^ w[18], w[21] = float_bits(p.m_batch);
  w[22] = std::uint32_t(p.met), w[23] = std::uint32_t(p.catcher);
}

PixelSums block_from_words(const std::uint32_t* w, int samples) {
  PixelSums p;
  for (int k = 0; k < 3; ++k) {
    p.objects[k] = bits_float(w[k]), p.with[k] = bits_float(w[3 + k]), p.without[k] = bits_float(w[6 + k] ^ w[3 + k]);
    p.albedo[k] = bits_float(w[9 + k]), p.normal[k] = bits_float(w[12 + k]);
  }
  p.coverage = bits_float(w[15]), p.depth = bits_float(w[16]), p.m_yy = bits_float(w[17]), p.m_ww = bits_float(w[18]);
  p.m_nn = bits_float(w[19] ^ w[18]), p.m_wn = bits_float(w[20] ^ w[18]), p.m_batch = bits_float(w[21]);
  p.met = std::int32_t(w[22]), p.catcher = std::int32_t(w[23]), p.samples = samples;
  p.batches = samples >= kBatchSamples ? samples / kBatchSamples : 0;
  p.batch_y = p.batches > 0 ? sum_y(p) : 0.0;
  return p;
}

// A pixel that adaptive sampling stopped holds the samples of the first k ≥ 1 passes, k ≤ passes done.
bool stopped_at_pass_end(const RenderState& st, std::int64_t n) {
  for (int k = 1; k <= st.passes_done; ++k)
    if (n == plan_pass_start(st, k) - st.sample_begin) return true;
  return false;
}

// Each pixel holds the samples [begin, begin + n) with n the samples of the passes done, plus
// the pass under way for the tiles before tiles_done.
void check_pixel_samples(const RenderState& st, const std::vector<std::uint32_t>& samples, const std::string& path) {
  const int begin = st.sample_begin;
  const int done = plan_pass_start(st, st.passes_done) - begin;
  const int next = st.passes_done < plan_passes(st) ? plan_pass_start(st, st.passes_done + 1) - begin : done;
  if (st.spp_done != done) throw InputError(path, "inconsistent checkpoint (samples done)");
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const std::int64_t n = samples[i];
    const bool stopped = !st.stopped.empty() && st.stopped[i];
    if (stopped ? !stopped_at_pass_end(st, n) : n != done && n != next)
      throw InputError(path, fmt::format("inconsistent checkpoint (pixel {})", i));
  }
}

// The header's plan: a size within kMaxImagePixels, a sample range within spp, passes and tiles
// within it.
void check_plan(const RenderState& st, const std::string& path) {
  const bool ok = st.width > 0 && st.height > 0 &&
                  std::uint64_t(st.width) * std::uint64_t(st.height) <= kMaxImagePixels && st.spp > 0 &&
                  st.sample_begin >= 0 && st.sample_begin < st.sample_end && st.sample_end <= st.spp &&
                  st.passes_done >= 0 && st.passes_done <= plan_passes(st) && st.tiles_done >= 0 &&
                  st.tiles_done < long(tiles_across(st.width)) * long(tiles_across(st.height));
  if (!ok) throw InputError(path, "inconsistent checkpoint (size, samples or passes)");
}

RenderState read_header(const std::string& in, std::size_t& at, const std::string& path) {
  RenderState st;
  for (int* v : {&st.width, &st.height, &st.spp, &st.sample_begin, &st.sample_end, &st.passes_done, &st.tiles_done,
                 &st.spp_done})
    *v = get<std::int32_t>(in, at, path);
  st.nonfinite = std::size_t(get<std::uint64_t>(in, at, path));
  st.noise_target = get<double>(in, at, path);
  if (!(st.noise_target >= 0 && st.noise_target <= 1)) throw InputError(path, "inconsistent checkpoint (noise target)");
  check_plan(st, path);
  return st;
}

// A frame's size, then the frame: its bytes within the file.
std::pair<const char*, std::size_t> frame_at(const std::string& in, std::size_t& at, const std::string& path) {
  const std::uint64_t size = get<std::uint64_t>(in, at, path);
  if (size > in.size() - at) throw InputError(path, "truncated checkpoint");
  const char* frame = in.data() + at;
  at += std::size_t(size);
  return {frame, std::size_t(size)};
}

// The first frame: every pixel's samples, then (adaptive) its stopped flag.
std::vector<std::uint32_t> read_pixel_frame(RenderState& st, const std::string& in, std::size_t& at,
                                            const std::string& path) {
  const std::size_t n = std::size_t(st.width) * std::size_t(st.height);
  const auto [frame, size] = frame_at(in, at, path);
  PlaneReader z(frame, size, 4 * std::uint64_t(n) + (st.noise_target > 0 ? n : 0), path);
  std::vector<std::uint32_t> samples = z.words(n);
  if (st.noise_target > 0) {
    st.stopped.resize(n);
    z.bytes(st.stopped.data(), n);
    if (std::any_of(st.stopped.begin(), st.stopped.end(), [](std::uint8_t b) { return b > 1; }))
      throw InputError(path, "inconsistent checkpoint (stopped pixels)");
  }
  z.finish();
  check_pixel_samples(st, samples, path);
  return samples;
}

// The second frame: the blocks of every pixel, the canonical ones of its samples (checked
// before, so that the frame's size is the state's), kChunkBlocks at a time. The pixels share a
// few sample counts (the passes' ends), whose decompositions are made once.
void read_block_frame(RenderState& st, const std::vector<std::uint32_t>& samples, const std::string& in,
                      std::size_t& at, const std::string& path) {
  std::map<std::uint32_t, std::vector<int>> sizes_of;
  std::uint64_t blocks = 0;
  for (std::uint32_t n : samples) {
    auto it = sizes_of.find(n);
    if (it == sizes_of.end())
      it = sizes_of.emplace(n, canonical_sizes(st.sample_begin, st.sample_begin + int(n))).first;
    blocks += it->second.size();
  }
  const auto [frame, size] = frame_at(in, at, path);
  PlaneReader z(frame, size, kBlockBytes * blocks, path);
  st.pixels.assign(samples.size(), {});
  std::vector<std::vector<std::uint32_t>> planes(kBlockWords);
  std::size_t pixel = 0;
  const std::vector<int>* sizes = samples.empty() ? nullptr : &sizes_of[samples[0]];
  std::uint32_t w[kBlockWords];
  for (std::size_t c = 0, left = std::size_t(blocks); left > 0; left -= c) {
    c = std::min(left, kChunkBlocks);
    for (auto& plane : planes) plane = z.words(c);
    for (std::size_t b = 0; b < c; ++b) {
      while (st.pixels[pixel].size() == sizes->size()) sizes = &sizes_of[samples[++pixel]];
      for (int k = 0; k < kBlockWords; ++k) w[k] = planes[std::size_t(k)][b];
      st.pixels[pixel].push_back(block_from_words(w, (*sizes)[st.pixels[pixel].size()]));
    }
  }
  z.finish();
}

void read_pixels(RenderState& st, const std::string& in, std::size_t& at, const std::string& path) {
  const std::vector<std::uint32_t> samples = read_pixel_frame(st, in, at, path);
  read_block_frame(st, samples, in, at, path);
  if (at != in.size()) throw InputError(path, "inconsistent checkpoint (bytes after the last pixel)");
}

std::string pixel_frame(const RenderState& st) {
  std::vector<std::uint32_t> samples(st.pixels.size());
  for (std::size_t i = 0; i < st.pixels.size(); ++i) {
    if (!canonical_blocks(st.pixels[i], st.sample_begin))
      throw std::invalid_argument(fmt::format("write_checkpoint: pixel {} has blocks of no canonical range", i));
    samples[i] = std::uint32_t(block_samples(st.pixels[i]));
  }
  PlaneWriter z(4 * std::uint64_t(samples.size()) + (st.noise_target > 0 ? st.stopped.size() : 0));
  z.words(samples);
  if (st.noise_target > 0) z.bytes(st.stopped.data(), st.stopped.size());
  return z.finish();
}

std::string block_frame(const RenderState& st) {
  std::uint64_t blocks = 0;
  for (const PixelBlocks& p : st.pixels) blocks += p.size();
  PlaneWriter z(kBlockBytes * blocks);
  std::vector<std::vector<std::uint32_t>> planes(kBlockWords);
  std::uint32_t w[kBlockWords];
  const auto flush = [&] {
    for (auto& plane : planes) z.words(plane), plane.clear();
  };
  for (const PixelBlocks& p : st.pixels)
    for (const PixelSums& b : p) {
      block_words(b, w);
      for (int k = 0; k < kBlockWords; ++k) planes[std::size_t(k)].push_back(w[k]);
      if (planes[0].size() == kChunkBlocks) flush();
    }
  if (!planes[0].empty()) flush();
  return z.finish();
}

void put_frame(std::string& out, const std::string& frame) {
  put(out, std::uint64_t(frame.size()));
  out += frame;
}

}  // namespace

std::string checkpoint_path(const std::string& image_path) { return image_path + ".checkpoint"; }

void write_checkpoint(const std::string& path, const RenderState& st, std::uint64_t fingerprint,
                      const std::string& settings) {
  if (!st.resumable)
    throw std::invalid_argument("write_checkpoint: the state was stopped within its tiles and cannot be resumed");
  std::string out(kMagic, sizeof(kMagic));
  put(out, kVersion), put(out, kBlockBytes), put(out, fingerprint);
  for (int v :
       {st.width, st.height, st.spp, st.sample_begin, st.sample_end, st.passes_done, st.tiles_done, st.spp_done})
    put(out, std::int32_t(v));
  put(out, std::uint64_t(st.nonfinite));
  put(out, st.noise_target);
  put(out, std::uint32_t(settings.size()));
  out += settings;
  put_frame(out, pixel_frame(st));
  put_frame(out, block_frame(st));
  Fnv1a sum;
  sum.bytes(out.data(), out.size());
  put(out, sum.digest());
  write_binary_file(path, out);
}

// The magic and the layout's version and block size: at `at` past them.
void check_layout(const std::string& in, std::size_t& at, const std::string& path) {
  if (in.size() < sizeof(kMagic) || std::memcmp(in.data(), kMagic, sizeof(kMagic)) != 0)
    throw InputError(path, "not an insitu checkpoint or part");
  at = sizeof(kMagic);
  if (get<std::uint32_t>(in, at, path) != kVersion || get<std::uint32_t>(in, at, path) != kBlockBytes)
    throw InputError(path, "a checkpoint of another insitu version");
}

StateFile read_state_file(const std::string& path) {
  if (!exists_quietly(path)) throw InputError(path, "no such file");
  if (is_directory_quietly(path)) throw InputError(path, "is a directory");
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  std::string in = ss.str();
  std::size_t at = 0;
  check_layout(in, at, path);
  if (in.size() - at < sizeof(std::uint64_t)) throw InputError(path, "truncated checkpoint");
  std::size_t end = in.size() - sizeof(std::uint64_t);
  const std::uint64_t stored = get<std::uint64_t>(in, end, path);
  Fnv1a sum;
  sum.bytes(in.data(), in.size() - sizeof(std::uint64_t));
  if (sum.digest() != stored)
    throw InputError(path,
                     "damaged: its checksum does not match its contents (it is kept as it is; render without "
                     "--resume to start again)");
  in.resize(in.size() - sizeof(std::uint64_t));
  return parse_state_bytes(in, path);
}

StateFile parse_state_bytes(const std::string& in, const std::string& path) {
  std::size_t at = 0;
  check_layout(in, at, path);
  StateFile file;
  file.fingerprint = get<std::uint64_t>(in, at, path);
  file.state = read_header(in, at, path);
  const std::uint32_t length = get<std::uint32_t>(in, at, path);
  if (in.size() - at < length) throw InputError(path, "truncated checkpoint");
  file.settings = in.substr(at, length);
  at += length;
  read_pixels(file.state, in, at, path);
  return file;
}

RenderState read_checkpoint(const std::string& path, std::uint64_t fingerprint) {
  if (!exists_quietly(path)) throw InputError(path, "no checkpoint to resume from (render without --resume)");
  StateFile file = read_state_file(path);
  if (file.fingerprint != fingerprint)
    throw InputError(path,
                     "a checkpoint of another scene, other inputs or other settings (spp, seed, integrator): "
                     "render without --resume to start again");
  return std::move(file.state);
}

}  // namespace insitu
