// A UV sphere as a .glb three ways, for tests/gltf_compression_test.cpp and bench/gltf_bench.cpp:
// plain, with EXT_meshopt_compression and KHR_mesh_quantization (as gltfpack writes it), and with
// KHR_draco_mesh_compression, each encoded by the library's own encoder.
#pragma once
#include <cmath>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "glb.h"
#include "uv_sphere.h"

namespace insitu::test {

using nlohmann::json;

inline json document(json primitive, json accessors, json views, json buffers, json extensions = json::array()) {
  json doc = {{"asset", {{"version", "2.0"}}},
              {"scene", 0},
              {"scenes", {{{"nodes", {0}}}}},
              {"nodes", {{{"mesh", 0}}}},
              {"meshes", {{{"primitives", {primitive}}}}},
              {"accessors", accessors},
              {"bufferViews", views},
              {"buffers", buffers}};
  if (!extensions.empty()) doc["extensionsUsed"] = extensions, doc["extensionsRequired"] = extensions;
  return doc;
}

inline json accessor(json view, int component_type, std::size_t count, const char* type, bool normalized = false) {
  json a = {{"componentType", component_type}, {"count", count}, {"type", type}};
  if (!view.is_null()) a["bufferView"] = view;
  if (normalized) a["normalized"] = true;
  return a;
}

// The sphere uncompressed: float POSITION, NORMAL and TEXCOORD_0, unsigned int indices.
inline std::string plain_sphere_glb(const UvSphere& s) {
  std::string bin;
  append(bin, s.pos), append(bin, s.nor), append(bin, s.uv), append(bin, s.idx);
  const std::size_t n = s.pos.size() / 3;
  const json prim = {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}};
  const json accessors = {accessor(0, 5126, n, "VEC3"), accessor(1, 5126, n, "VEC3"), accessor(2, 5126, n, "VEC2"),
                          accessor(3, 5125, s.idx.size(), "SCALAR")};
  const json views = {{{"buffer", 0}, {"byteLength", 12 * n}},
                      {{"buffer", 0}, {"byteOffset", 12 * n}, {"byteLength", 12 * n}},
                      {{"buffer", 0}, {"byteOffset", 24 * n}, {"byteLength", 8 * n}},
                      {{"buffer", 0}, {"byteOffset", 32 * n}, {"byteLength", 4 * s.idx.size()}}};
  return glb(document(prim, accessors, views, {{{"byteLength", bin.size()}}}), bin);
}

// One meshopt-encoded buffer view: its bytes appended to `bin` (4-aligned), its view over the
// fallback buffer 1 at `*fallback_offset`.
inline json meshopt_view(std::string& bin, std::size_t* fallback_offset, const std::string& encoded, std::size_t count,
                         std::size_t stride, const char* mode, const char* filter = "NONE") {
  const std::size_t at = bin.size();
  bin += encoded;
  while (bin.size() % 4) bin += '\0';
  json view = {{"buffer", 1},
               {"byteOffset", *fallback_offset},
               {"byteLength", count * stride},
               {"extensions",
                {{"EXT_meshopt_compression",
                  {{"buffer", 0},
                   {"byteOffset", at},
                   {"byteLength", encoded.size()},
                   {"byteStride", stride},
                   {"count", count},
                   {"mode", mode},
                   {"filter", filter}}}}}};
  if (std::string(mode) == "ATTRIBUTES") view["byteStride"] = stride;
  *fallback_offset += count * stride;
  return view;
}

template <class T>
inline std::string encode_vertices(const std::vector<T>& v, std::size_t count) {
  std::string out(meshopt_encodeVertexBufferBound(count, v.size() * sizeof(T) / count), '\0');
  out.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(out.data()), out.size(), v.data(), count,
                                        v.size() * sizeof(T) / count));
  return out;
}

// The sphere as gltfpack writes it: positions as shorts in tenths of a millimetre (the node
// scales them back), normals as octahedral bytes, UVs as normalized unsigned shorts, indices by
// the triangle codec; the fallback buffer has no uri.
inline std::string meshopt_sphere_glb(const UvSphere& s) {
  const std::size_t n = s.pos.size() / 3;
  std::vector<std::int16_t> pos(4 * n, 0);
  std::vector<float> nor4(4 * n, 0.0f);
  std::vector<std::int8_t> oct(4 * n);
  std::vector<std::uint16_t> uv(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      pos[4 * i + k] = std::int16_t(std::lround(s.pos[3 * i + k] * 10000));
      nor4[4 * i + k] = s.nor[3 * i + k];
    }
    for (int k = 0; k < 2; ++k) uv[2 * i + k] = std::uint16_t(std::lround(s.uv[2 * i + k] * 65535));
  }
  meshopt_encodeFilterOct(oct.data(), n, 4, 8, nor4.data());
  std::string idx(meshopt_encodeIndexBufferBound(s.idx.size(), n), '\0');
  idx.resize(
      meshopt_encodeIndexBuffer(reinterpret_cast<unsigned char*>(idx.data()), idx.size(), s.idx.data(), s.idx.size()));
  std::string bin;
  std::size_t fallback = 0;
  const json views = {meshopt_view(bin, &fallback, encode_vertices(pos, n), n, 8, "ATTRIBUTES"),
                      meshopt_view(bin, &fallback, encode_vertices(oct, n), n, 4, "ATTRIBUTES", "OCTAHEDRAL"),
                      meshopt_view(bin, &fallback, encode_vertices(uv, n), n, 4, "ATTRIBUTES"),
                      meshopt_view(bin, &fallback, idx, s.idx.size(), 4, "TRIANGLES")};
  const json prim = {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}};
  const json accessors = {accessor(0, 5122, n, "VEC3"), accessor(1, 5120, n, "VEC3", true),
                          accessor(2, 5123, n, "VEC2", true), accessor(3, 5125, s.idx.size(), "SCALAR")};
  const json buffers = {
      {{"byteLength", bin.size()}},
      {{"byteLength", fallback}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};
  json doc = document(prim, accessors, views, buffers, {"EXT_meshopt_compression", "KHR_mesh_quantization"});
  doc["nodes"][0]["scale"] = {1e-4, 1e-4, 1e-4};
  return glb(doc, bin);
}

// The sphere through Draco's encoder at 14 bits for positions (over the bounding box's largest
// side), 10 for normals and 12 for UVs.
inline std::string draco_sphere_glb(const UvSphere& s) {
  const std::size_t faces = s.idx.size() / 3;
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(int(faces));
  const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int nor = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  const int uv = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  for (std::size_t f = 0; f < faces; ++f) {
    const std::uint32_t* c = &s.idx[3 * f];
    const draco::FaceIndex fi(static_cast<std::uint32_t>(f));
    builder.SetAttributeValuesForFace(pos, fi, &s.pos[3 * c[0]], &s.pos[3 * c[1]], &s.pos[3 * c[2]]);
    builder.SetAttributeValuesForFace(nor, fi, &s.nor[3 * c[0]], &s.nor[3 * c[1]], &s.nor[3 * c[2]]);
    builder.SetAttributeValuesForFace(uv, fi, &s.uv[2 * c[0]], &s.uv[2 * c[1]], &s.uv[2 * c[2]]);
  }
  const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
  draco::EncoderBuffer encoded;
  if (!encoder.EncodeMeshToBuffer(*mesh, &encoded).ok()) return {};
  const std::string bin(encoded.data(), encoded.size());
  const std::size_t n = mesh->num_points();
  const json ids = {{"POSITION", mesh->attribute(pos)->unique_id()},
                    {"NORMAL", mesh->attribute(nor)->unique_id()},
                    {"TEXCOORD_0", mesh->attribute(uv)->unique_id()}};
  const json prim = {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
                     {"indices", 3},
                     {"extensions", {{"KHR_draco_mesh_compression", {{"bufferView", 0}, {"attributes", ids}}}}}};
  const json accessors = {accessor(nullptr, 5126, n, "VEC3"), accessor(nullptr, 5126, n, "VEC3"),
                          accessor(nullptr, 5126, n, "VEC2"), accessor(nullptr, 5125, s.idx.size(), "SCALAR")};
  const json doc = document(prim, accessors, {{{"buffer", 0}, {"byteLength", bin.size()}}},
                            {{{"byteLength", bin.size()}}}, {"KHR_draco_mesh_compression"});
  return glb(doc, bin);
}

}  // namespace insitu::test
