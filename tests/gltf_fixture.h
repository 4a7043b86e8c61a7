// glTF files written by tests: base64 for data URIs, raw little-endian arrays, and a UV sphere
// with a material (the principled model's Cycles comparison in blender_export_test.cpp).
#pragma once
#include <cmath>
#include <cstdint>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/math.h"
#include "glb.h"
#include "test_util.h"
#include "uv_sphere.h"

namespace insitu::test {

// RFC 4648 base64, for data URIs.
inline std::string base64(const std::string& bytes) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  auto byte = [&](std::size_t i) { return i < bytes.size() ? std::uint32_t(std::uint8_t(bytes[i])) : 0u; };
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t v = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
    const std::size_t digits = std::min<std::size_t>(4, 1 + (bytes.size() - i) * 4 / 3);  // 2, 3 or 4
    for (std::size_t k = 0; k < 4; ++k) out += k < digits ? kDigits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// A UV sphere (`rings` × 2·`rings` quads, smooth normals) of `radius` about `centre`, with one
// material (a glTF material object), written as name.gltf and name.bin in dir.
inline std::string write_gltf_sphere(const TempDir& dir, const std::string& name, const Vec3f& centre, float radius,
                                     const nlohmann::json& material, int rings = 24) {
  const float c[3] = {centre.x(), centre.y(), centre.z()};
  const UvSphere sphere = make_uv_sphere(rings, 2 * rings, c, radius);
  const std::vector<float>&pos = sphere.pos, &nor = sphere.nor;
  const std::vector<std::uint32_t>& idx = sphere.idx;
  std::string bin;
  append(bin, pos), append(bin, nor), append(bin, idx);
  const std::size_t n = pos.size() / 3, o_idx = 24 * n;
  const nlohmann::json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}, {"material", 0}}}}}}},
      {"materials", {material}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}},
        {{"bufferView", 0}, {"byteOffset", 12 * n}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5125}, {"count", idx.size()}, {"type", "SCALAR"}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteLength", o_idx}},
        {{"buffer", 0}, {"byteOffset", o_idx}, {"byteLength", 4 * idx.size()}}}},
      {"buffers", {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}}}};
  std::ofstream(dir.file(name + ".bin"), std::ios::binary) << bin;
  return dir.write(name + ".gltf", doc.dump());
}

}  // namespace insitu::test
