#include "render/checkpoint.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "core/fnv1a.h"
#include "core/file_check.h"
#include "core/text_file.h"
#include "render/pixel_blocks.h"
#include "render/pixel_variance.h"

namespace insitu {
namespace {

constexpr char kMagic[8] = {'I', 'N', 'S', 'I', 'T', 'U', 'C', 'K'};
constexpr std::uint32_t kVersion = 7;

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

// One pixel's sums, field by field (Eigen's types are not trivially copyable): 22 floats and 3
// int32. A block's batches and batch_y follow from its samples and sums (render_state.h).
constexpr std::uint32_t kPixelBytes = 22 * 4 + 3 * 4;

void put_sums(std::string& out, const PixelSums& p) {
  for (const Rgb* c : {&p.objects, &p.with, &p.without, &p.albedo})
    for (int k = 0; k < 3; ++k) put(out, (*c)[k]);
  for (int k = 0; k < 3; ++k) put(out, p.normal[k]);
  for (float f : {p.coverage, p.depth, p.m_yy, p.m_ww, p.m_nn, p.m_wn, p.m_batch}) put(out, f);
  put(out, std::int32_t(p.met)), put(out, std::int32_t(p.catcher)), put(out, std::int32_t(p.samples));
}

PixelSums get_sums(const std::string& in, std::size_t& at, const std::string& path) {
  PixelSums p;
  for (Rgb* c : {&p.objects, &p.with, &p.without, &p.albedo})
    for (int k = 0; k < 3; ++k) (*c)[k] = get<float>(in, at, path);
  for (int k = 0; k < 3; ++k) p.normal[k] = get<float>(in, at, path);
  for (float* f : {&p.coverage, &p.depth, &p.m_yy, &p.m_ww, &p.m_nn, &p.m_wn, &p.m_batch})
    *f = get<float>(in, at, path);
  p.met = get<std::int32_t>(in, at, path), p.catcher = get<std::int32_t>(in, at, path);
  p.samples = get<std::int32_t>(in, at, path);
  p.batches = p.samples >= kBatchSamples ? p.samples / kBatchSamples : 0;
  p.batch_y = p.batches > 0 ? sum_y(p) : 0.0;
  return p;
}

// A pixel that adaptive sampling stopped holds the samples of the first k ≥ 1 passes, k ≤ passes done.
bool stopped_at_pass_end(const RenderState& st, int n) {
  for (int k = 1; k <= st.passes_done; ++k)
    if (n == plan_pass_start(st, k) - st.sample_begin) return true;
  return false;
}

// Each pixel holds the canonical blocks of [begin, begin + n) with n the samples of the passes
// done, plus the pass under way for the tiles before tiles_done.
void check_pixels(const RenderState& st, const std::string& path) {
  const int begin = st.sample_begin;
  const int done = plan_pass_start(st, st.passes_done) - begin;
  const int next = st.passes_done < plan_passes(st) ? plan_pass_start(st, st.passes_done + 1) - begin : done;
  if (st.spp_done != done) throw InputError(path, "inconsistent checkpoint (samples done)");
  for (std::size_t i = 0; i < st.pixels.size(); ++i) {
    const int n = block_samples(st.pixels[i]);
    const bool stopped = !st.stopped.empty() && st.stopped[i];
    if ((stopped ? !stopped_at_pass_end(st, n) : n != done && n != next) || !canonical_blocks(st.pixels[i], begin))
      throw InputError(path, fmt::format("inconsistent checkpoint (pixel {})", i));
  }
}

// The header's plan: a size, a sample range within spp, passes and tiles within it.
void check_plan(const RenderState& st, const std::string& path) {
  const bool ok = st.width > 0 && st.height > 0 && st.spp > 0 && st.sample_begin >= 0 &&
                  st.sample_begin < st.sample_end && st.sample_end <= st.spp && st.passes_done >= 0 &&
                  st.passes_done <= plan_passes(st) && st.tiles_done >= 0 &&
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

// One pixel's blocks. Their samples lie within the part's range [sample_begin, sample_end), summed
// in 64 bits: the file's counts are not trusted to fit an int's sum.
PixelBlocks read_blocks(const RenderState& st, const std::string& in, std::size_t& at, const std::string& path) {
  const std::int32_t count = get<std::int32_t>(in, at, path);
  if (count < 0 || count > 64 || (in.size() - at) / kPixelBytes < std::size_t(count))
    throw InputError(path, "truncated checkpoint");
  PixelBlocks blocks;
  blocks.reserve(std::size_t(count));
  std::int64_t samples = 0;
  for (int k = 0; k < count; ++k) {
    blocks.push_back(get_sums(in, at, path));
    samples += blocks.back().samples;
    if (blocks.back().samples < 1 || samples > st.sample_end - st.sample_begin)
      throw InputError(path, "inconsistent checkpoint (samples in a pixel)");
  }
  return blocks;
}

void read_pixels(RenderState& st, const std::string& in, std::size_t& at, const std::string& path) {
  const std::size_t n = std::size_t(st.width) * std::size_t(st.height);
  if ((in.size() - at) / 4 < n) throw InputError(path, "truncated checkpoint");
  st.pixels.resize(n);
  for (PixelBlocks& blocks : st.pixels) blocks = read_blocks(st, in, at, path);
  if (st.noise_target > 0) {
    if (in.size() - at < n) throw InputError(path, "truncated checkpoint");
    st.stopped.assign(in.begin() + std::ptrdiff_t(at), in.begin() + std::ptrdiff_t(at + n));
    at += n;
    if (std::any_of(st.stopped.begin(), st.stopped.end(), [](std::uint8_t b) { return b > 1; }))
      throw InputError(path, "inconsistent checkpoint (stopped pixels)");
  }
  if (at != in.size()) throw InputError(path, "inconsistent checkpoint (bytes after the last pixel)");
  check_pixels(st, path);
}

}  // namespace

std::string checkpoint_path(const std::string& image_path) { return image_path + ".checkpoint"; }

void write_checkpoint(const std::string& path, const RenderState& st, std::uint64_t fingerprint,
                      const std::string& settings) {
  if (!st.resumable)
    throw std::invalid_argument("write_checkpoint: the state was stopped within its tiles and cannot be resumed");
  std::string out(kMagic, sizeof(kMagic));
  put(out, kVersion), put(out, kPixelBytes), put(out, fingerprint);
  for (int v :
       {st.width, st.height, st.spp, st.sample_begin, st.sample_end, st.passes_done, st.tiles_done, st.spp_done})
    put(out, std::int32_t(v));
  put(out, std::uint64_t(st.nonfinite));
  put(out, st.noise_target);
  put(out, std::uint32_t(settings.size()));
  out += settings;
  out.reserve(out.size() + st.pixels.size() * (4 + 3 * kPixelBytes));
  for (const PixelBlocks& blocks : st.pixels) {
    put(out, std::int32_t(blocks.size()));
    for (const PixelSums& p : blocks) put_sums(out, p);
  }
  if (st.noise_target > 0) out.append(st.stopped.begin(), st.stopped.end());
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
  if (get<std::uint32_t>(in, at, path) != kVersion || get<std::uint32_t>(in, at, path) != kPixelBytes)
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
