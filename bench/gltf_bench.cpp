// Loading catalogue furniture (issue 49's goal: a 100 k-triangle .glb with 4 k textures in under
// 2 s on 2 cores):
//   build/bench/insitu_bench --benchmark_filter=LoadGltf
// The asset is made once per run in a temporary folder: a UV sphere of 99 904 triangles with
// normals and UVs, a 4096² base-colour PNG and a 4096² metallic-roughness PNG (noise, so that
// PNG cannot compress them to nothing), all in one .glb. The counter peak_MB is the load's
// resident-memory peak.
#include <benchmark/benchmark.h>

#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "core/image.h"
#include "peak_memory.h"
#include "render/gltf_mesh.h"
#include "render/tangents.h"
#include "../tests/gltf_compressed_fixture.h"
#include "../tests/uv_sphere.h"

namespace {
using namespace insitu;
namespace fs = std::filesystem;

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

template <class T>
void put(std::string& bytes, const std::vector<T>& v) {
  bytes.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  while (bytes.size() % 4) bytes += '\0';
}

std::string noise_png(const fs::path& dir, const std::string& name, int size, std::uint32_t seed) {
  Image img(size, size, 3);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> level(0, 255);
  for (float& v : img.data) v = float(level(rng)) / 255.0f;
  const std::string path = (dir / name).string();
  write_image(path, img);
  return file_bytes(path);
}

// The .glb, written once: rings × 2·rings quads.
std::string furniture_glb() {
  static const std::string path = [] {
    const fs::path dir = fs::temp_directory_path() / "insitu-bench-gltf";
    fs::create_directories(dir);
    const int rings = 224, segments = 224;  // 2 · 224 · (224 − 1) = 99 904 triangles
    const float centre[3] = {0, 0, 0};
    const test::UvSphere sphere = test::make_uv_sphere(rings, segments, centre, 0.5f);
    const auto &pos = sphere.pos, &nor = sphere.nor, &uv = sphere.uv;
    const auto& idx = sphere.idx;
    std::string bin;
    std::vector<std::size_t> at;
    for (const auto* v : {&pos, &nor}) at.push_back(bin.size()), put(bin, *v);
    at.push_back(bin.size()), put(bin, uv);
    at.push_back(bin.size()), put(bin, idx);
    const std::string base = noise_png(dir, "base.png", 4096, 1), mr = noise_png(dir, "mr.png", 4096, 2);
    at.push_back(bin.size()), bin += base;
    while (bin.size() % 4) bin += '\0';
    at.push_back(bin.size()), bin += mr;
    while (bin.size() % 4) bin += '\0';
    const std::size_t n = pos.size() / 3;
    using nlohmann::json;
    json views = json::array();
    const std::size_t lengths[] = {12 * n, 12 * n, 8 * n, 4 * idx.size(), base.size(), mr.size()};
    for (std::size_t k = 0; k < 6; ++k)
      views.push_back({{"buffer", 0}, {"byteOffset", at[k]}, {"byteLength", lengths[k]}});
    const json doc = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes",
         {{{"primitives",
            {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
              {"indices", 3},
              {"material", 0}}}}}}},
        {"materials",
         {{{"pbrMetallicRoughness",
            {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 1}}}}}}}},
        {"textures", {{{"source", 0}}, {{"source", 1}}}},
        {"images", {{{"bufferView", 4}, {"mimeType", "image/png"}}, {{"bufferView", 5}, {"mimeType", "image/png"}}}},
        {"accessors",
         {{{"bufferView", 0}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}},
          {{"bufferView", 1}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}},
          {{"bufferView", 2}, {"componentType", 5126}, {"count", n}, {"type", "VEC2"}},
          {{"bufferView", 3}, {"componentType", 5125}, {"count", idx.size()}, {"type", "SCALAR"}}}},
        {"bufferViews", views},
        {"buffers", {{{"byteLength", bin.size()}}}}};
    const std::string glb = test::glb(doc, bin);
    const std::string out = (dir / "furniture.glb").string();
    std::ofstream(out, std::ios::binary) << glb;
    return out;
  }();
  return path;
}

void BM_LoadGltf(benchmark::State& state) {
  const std::string path = furniture_glb();
  double peak_mb = 0;
  std::size_t triangles = 0;
  for (auto _ : state) {
    bench::PeakMemory peak;
    Warnings w;
    const Mesh mesh = load_gltf(path, w);
    triangles = mesh.triangles.size();
    peak_mb = peak.peak_mb();
  }
  state.counters["triangles"] = double(triangles);
  state.counters["peak_MB"] = peak_mb;
}
BENCHMARK(BM_LoadGltf)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// One 4096² noise PNG decoded from memory as a texture: as floats (0, read_image_memory, how
// textures were read before 2026-11-29) and as its bytes (1, read_texture_memory, how they are).
//   build/bench/insitu_bench --benchmark_filter=DecodeTexture
void BM_DecodeTexture(benchmark::State& state) {
  const fs::path dir = fs::temp_directory_path() / "insitu-bench-gltf";
  fs::create_directories(dir);
  const std::string png = noise_png(dir, "decode.png", 4096, 3);
  const std::vector<unsigned char> bytes(png.begin(), png.end());
  double peak_mb = 0;
  for (auto _ : state) {
    bench::PeakMemory peak;
    const ImageFile file = state.range(0)
                               ? read_texture_memory("t.png", bytes, AlphaChannel::kKeep)
                               : read_image_memory("t.png", bytes, PixelGrid::kAsStored, AlphaChannel::kKeep);
    benchmark::DoNotOptimize(file.stored.data.data());
    benchmark::DoNotOptimize(file.stored_bytes.data.data());
    peak_mb = peak.peak_mb();
  }
  state.counters["peak_MB"] = peak_mb;
}
BENCHMARK(BM_DecodeTexture)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);

// Geometry alone, the same 99 904 triangles: plain floats (0), meshopt with quantized attributes
// as gltfpack writes them (1), Draco at 14/10/12 bits (2). The counter file_kB is the .glb's size.
//   build/bench/insitu_bench --benchmark_filter=LoadCompressedGltf
void BM_LoadCompressedGltf(benchmark::State& state) {
  const float centre[3] = {0, 0, 0};
  const test::UvSphere sphere = test::make_uv_sphere(224, 224, centre, 0.5f);
  const std::string bytes = state.range(0) == 0   ? test::plain_sphere_glb(sphere)
                            : state.range(0) == 1 ? test::meshopt_sphere_glb(sphere)
                                                  : test::draco_sphere_glb(sphere);
  const fs::path path = fs::temp_directory_path() / fmt::format("insitu-bench-compressed-{}.glb", state.range(0));
  std::ofstream(path, std::ios::binary) << bytes;
  std::size_t triangles = 0;
  for (auto _ : state) {
    Warnings w;
    triangles = load_gltf(path.string(), w).triangles.size();
  }
  fs::remove(path);
  state.counters["triangles"] = double(triangles);
  state.counters["file_kB"] = double(bytes.size()) / 1e3;
}
BENCHMARK(BM_LoadCompressedGltf)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime();

// MikkTSpace tangents for a normal map (render/tangents.h), generated at load where a file has no
// TANGENT: the same 99 904-triangle sphere, every vertex shared by six corners.
//   build/bench/insitu_bench --benchmark_filter=MikkTSpace
void BM_MikkTSpaceTangents(benchmark::State& state) {
  const float centre[3] = {0, 0, 0};
  const test::UvSphere s = test::make_uv_sphere(224, 224, centre, 0.5f);
  const Mesh m = test::uv_sphere_mesh(s);
  for (auto _ : state) benchmark::DoNotOptimize(mikktspace_tangents(m, 0));
  state.counters["triangles"] = double(m.triangles.size());
}
BENCHMARK(BM_MikkTSpaceTangents)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
