#include "render/checkpoint.h"

#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/file_check.h"
#include "core/text_file.h"

namespace insitu {
namespace {

constexpr char kMagic[8] = {'I', 'N', 'S', 'I', 'T', 'U', 'C', 'K'};
constexpr std::uint32_t kVersion = 2;

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

// One pixel's sums, field by field (Eigen's types are not trivially copyable): 15 floats, 9
// doubles, 3 int32.
constexpr std::uint32_t kPixelBytes = 15 * 4 + 9 * 8 + 3 * 4;

void put_sums(std::string& out, const PixelSums& p) {
  for (const Rgb* c : {&p.objects, &p.with, &p.without, &p.albedo})
    for (int k = 0; k < 3; ++k) put(out, (*c)[k]);
  for (int k = 0; k < 3; ++k) put(out, p.normal[k]);
  for (double d : {p.coverage, p.depth, p.y, p.y2, p.w, p.n, p.w2, p.n2, p.wn}) put(out, d);
  put(out, std::int32_t(p.met)), put(out, std::int32_t(p.catcher)), put(out, std::int32_t(p.samples));
}

PixelSums get_sums(const std::string& in, std::size_t& at, const std::string& path) {
  PixelSums p;
  for (Rgb* c : {&p.objects, &p.with, &p.without, &p.albedo})
    for (int k = 0; k < 3; ++k) (*c)[k] = get<float>(in, at, path);
  for (int k = 0; k < 3; ++k) p.normal[k] = get<float>(in, at, path);
  for (double* d : {&p.coverage, &p.depth, &p.y, &p.y2, &p.w, &p.n, &p.w2, &p.n2, &p.wn}) *d = get<double>(in, at, path);
  p.met = get<std::int32_t>(in, at, path), p.catcher = get<std::int32_t>(in, at, path);
  p.samples = get<std::int32_t>(in, at, path);
  return p;
}

}  // namespace

std::string checkpoint_path(const std::string& image_path) { return image_path + ".checkpoint"; }

void write_checkpoint(const std::string& path, const RenderState& st, std::uint64_t fingerprint) {
  std::string out(kMagic, sizeof(kMagic));
  put(out, kVersion), put(out, kPixelBytes), put(out, fingerprint);
  for (int v : {st.width, st.height, st.spp, st.passes_done, st.tiles_done, st.spp_done}) put(out, std::int32_t(v));
  put(out, std::uint64_t(st.nonfinite));
  out.reserve(out.size() + st.sums.size() * kPixelBytes);
  for (const PixelSums& p : st.sums) put_sums(out, p);
  write_binary_file(path, out);
}

RenderState read_checkpoint(const std::string& path, std::uint64_t fingerprint) {
  if (!exists_quietly(path)) throw InputError(path, "no checkpoint to resume from (render without --resume)");
  if (is_directory_quietly(path)) throw InputError(path, "is a directory");
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string in = ss.str();
  if (in.size() < sizeof(kMagic) || std::memcmp(in.data(), kMagic, sizeof(kMagic)) != 0)
    throw InputError(path, "not an insitu checkpoint");
  std::size_t at = sizeof(kMagic);
  if (get<std::uint32_t>(in, at, path) != kVersion || get<std::uint32_t>(in, at, path) != kPixelBytes)
    throw InputError(path, "a checkpoint of another insitu version");
  if (get<std::uint64_t>(in, at, path) != fingerprint)
    throw InputError(path, "a checkpoint of another scene, other inputs or other settings (spp, seed, integrator): "
                           "render without --resume to start again");
  RenderState st;
  st.width = get<std::int32_t>(in, at, path), st.height = get<std::int32_t>(in, at, path);
  st.spp = get<std::int32_t>(in, at, path), st.passes_done = get<std::int32_t>(in, at, path);
  st.tiles_done = get<std::int32_t>(in, at, path);
  st.spp_done = get<std::int32_t>(in, at, path);
  st.nonfinite = std::size_t(get<std::uint64_t>(in, at, path));
  const std::size_t n = std::size_t(std::max(0, st.width)) * std::size_t(std::max(0, st.height));
  if (in.size() - at != n * kPixelBytes) throw InputError(path, "truncated checkpoint");
  st.sums.reserve(n);
  for (std::size_t i = 0; i < n; ++i) st.sums.push_back(get_sums(in, at, path));
  return st;
}

}  // namespace insitu
