#include "render/gltf_decompress.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <draco/compression/decode.h>
#include <fmt/format.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string_view>

#include "core/error.h"

namespace insitu {
namespace {

constexpr std::uint32_t kGlbMagic = 0x46546C67u, kJsonChunk = 0x4E4F534Au;
constexpr double kMaxDecodedBytes = double(1u << 30), kMaxExpansion = 64;

// A fallback buffer ({"byteLength": n, "extensions": {"EXT_meshopt_compression": {"fallback":
// true}}}, no uri) gets 4 bytes of data; a Draco primitive's index accessor without a buffer view
// (decoding gives it one) names the Draco stream's, which tinygltf demands.
bool prepare(nlohmann::json& doc) {
  if (!doc.is_object()) return false;
  bool changed = false;
  if (doc.contains("buffers") && doc["buffers"].is_array())
    for (auto& buffer : doc["buffers"]) {
      if (!buffer.is_object() || buffer.contains("uri") ||
          !buffer.value("/extensions/EXT_meshopt_compression/fallback"_json_pointer, false))
        continue;
      buffer["uri"] = "data:application/octet-stream;base64,AAAAAA==";
      buffer["byteLength"] = 4;
      changed = true;
    }
  if (!doc.contains("meshes") || !doc["meshes"].is_array() || !doc.contains("accessors") ||
      !doc["accessors"].is_array())
    return changed;
  auto& accessors = doc["accessors"];
  for (const auto& mesh : doc["meshes"])
    for (const auto& prim : mesh.value("primitives", nlohmann::json::array())) {
      const auto view = prim.value("/extensions/KHR_draco_mesh_compression/bufferView"_json_pointer, -1);
      const auto indices = prim.value("indices", -1);
      if (view < 0 || indices < 0 || std::size_t(indices) >= accessors.size() || !accessors[indices].is_object() ||
          accessors[indices].contains("bufferView"))
        continue;
      accessors[indices]["bufferView"] = view;
      changed = true;
    }
  return changed;
}

std::uint32_t u32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  if (at + 4 <= s.size()) std::memcpy(&v, s.data() + at, 4);
  return v;
}

void put_u32(std::string& s, std::uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); }

bool mentions_compression(std::string_view json) {
  return json.find("EXT_meshopt_compression") != json.npos || json.find("KHR_draco_mesh_compression") != json.npos;
}

// GLB: a 12-byte header (magic, version, length), then chunks of (length, type, bytes); the first
// is the JSON. A container tinygltf would refuse is passed on unchanged for it to refuse.
std::string reprepare_glb(std::string bytes) {
  const std::uint32_t json_length = u32(bytes, 12);
  if (u32(bytes, 0) != kGlbMagic || u32(bytes, 16) != kJsonChunk || 20 + std::uint64_t(json_length) > bytes.size())
    return bytes;
  if (!mentions_compression(std::string_view(bytes).substr(20, json_length))) return bytes;
  nlohmann::json doc = nlohmann::json::parse(bytes.substr(20, json_length), nullptr, false);
  if (!prepare(doc)) return bytes;
  std::string json = doc.dump();
  json.append((4 - json.size() % 4) % 4, ' ');
  const std::string rest = bytes.substr(20 + json_length);
  std::string out = bytes.substr(0, 8);
  put_u32(out, std::uint32_t(12 + 8 + json.size() + rest.size()));
  put_u32(out, std::uint32_t(json.size()));
  put_u32(out, kJsonChunk);
  return out + json + rest;
}

// An integer member of an extension object, within [lo, hi].
double member(const tinygltf::Value& v, const char* key, const std::string& where, double lo, double hi,
              double fallback = NAN) {
  if (!v.Has(key)) {
    if (!std::isnan(fallback)) return fallback;
    throw InputError(where, fmt::format("no {}", key));
  }
  const tinygltf::Value& m = v.Get(key);
  const double x = m.IsNumber() ? m.GetNumberAsDouble() : NAN;
  if (!(x >= lo && x <= hi) || x != std::floor(x))
    throw InputError(where + "." + key, fmt::format("must be an integer in [{}, {}]", lo, hi));
  return x;
}

std::string string_member(const tinygltf::Value& v, const char* key, const char* fallback) {
  return v.Has(key) && v.Get(key).IsString() ? v.Get(key).Get<std::string>() : fallback;
}

// The bytes [offset, offset + length) of buffer `index`, checked.
const unsigned char* bytes_of(const tinygltf::Model& model, double index, double offset, double length,
                              const std::string& where) {
  if (index >= double(model.buffers.size()))
    throw InputError(where + ".buffer", fmt::format("buffer {} out of range", index));
  const auto& data = model.buffers[std::size_t(index)].data;
  if (offset + length > double(data.size()))
    throw InputError(where, fmt::format("bytes {}..{} run past the end of buffer {} ({} bytes)", offset,
                                        offset + length, index, data.size()));
  return data.data() + std::size_t(offset);
}

std::vector<unsigned char> meshopt_view(const tinygltf::Model& model, const tinygltf::Value& e,
                                        const std::string& where) {
  const double buffer = member(e, "buffer", where, 0, 1e9), offset = member(e, "byteOffset", where, 0, 4e9, 0);
  const double length = member(e, "byteLength", where, 1, 4e9), stride = member(e, "byteStride", where, 1, 256);
  const double count = member(e, "count", where, 1, 4e9);
  const std::string mode = string_member(e, "mode", ""), filter = string_member(e, "filter", "NONE");
  const unsigned char* src = bytes_of(model, buffer, offset, length, where);
  if (count * stride > std::min(kMaxDecodedBytes, kMaxExpansion * length))
    throw InputError(where, fmt::format("{} × {} bytes cannot come from {} encoded bytes", count, stride, length));
  std::vector<unsigned char> out(std::size_t(count * stride));
  const std::size_t n = std::size_t(count), s = std::size_t(stride), l = std::size_t(length);
  int status = -1;
  if (mode == "ATTRIBUTES") {
    if (s % 4 == 0) status = meshopt_decodeVertexBuffer(out.data(), n, s, src, l);
  } else if (mode == "TRIANGLES") {
    if ((s == 2 || s == 4) && n % 3 == 0) status = meshopt_decodeIndexBuffer(out.data(), n, s, src, l);
  } else if (mode == "INDICES") {
    if (s == 2 || s == 4) status = meshopt_decodeIndexSequence(out.data(), n, s, src, l);
  } else {
    throw InputError(where + ".mode", fmt::format("unknown mode \"{}\"", mode));
  }
  if (status != 0)
    throw InputError(where, fmt::format("meshoptimizer cannot decode it as {} of {} bytes each", mode, s));
  if (filter == "OCTAHEDRAL" && (s == 4 || s == 8)) return meshopt_decodeFilterOct(out.data(), n, s), out;
  if (filter == "QUATERNION" && s == 8) return meshopt_decodeFilterQuat(out.data(), n, s), out;
  if (filter == "EXPONENTIAL" && s % 4 == 0) return meshopt_decodeFilterExp(out.data(), n, s), out;
  if (filter != "NONE") throw InputError(where + ".filter", fmt::format("filter {} with {} bytes", filter, s));
  return out;
}

int add_buffer(tinygltf::Model& model, std::vector<unsigned char> data) {
  model.buffers.emplace_back();
  model.buffers.back().data = std::move(data);
  return int(model.buffers.size() - 1);
}

void decompress_meshopt(tinygltf::Model& model, const std::string& path) {
  for (std::size_t i = 0; i < model.bufferViews.size(); ++i) {
    const auto it = model.bufferViews[i].extensions.find("EXT_meshopt_compression");
    if (it == model.bufferViews[i].extensions.end()) continue;
    const std::string where = fmt::format("{}: $.bufferViews[{}].extensions.EXT_meshopt_compression", path, i);
    std::vector<unsigned char> data = meshopt_view(model, it->second, where);
    tinygltf::BufferView& view = model.bufferViews[i];
    const double stride = member(it->second, "byteStride", where, 1, 256);
    if (view.byteStride == 0 && string_member(it->second, "mode", "") == "ATTRIBUTES")
      view.byteStride = std::size_t(stride);
    view.byteLength = data.size();
    view.byteOffset = 0;
    view.buffer = add_buffer(model, std::move(data));
  }
}

// A new accessor of `count` elements of `components` floats (or, components == 0, unsigned int
// scalars) over a buffer of its own.
void rewrite_accessor(tinygltf::Model& model, tinygltf::Accessor& a, std::vector<unsigned char> data, std::size_t count,
                      int components) {
  tinygltf::BufferView view;
  view.byteLength = data.size();
  view.buffer = add_buffer(model, std::move(data));
  model.bufferViews.push_back(view);
  a.bufferView = int(model.bufferViews.size() - 1);
  a.byteOffset = 0;
  a.count = count;
  a.normalized = false;
  a.sparse = {};
  a.componentType = components == 0 ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT : TINYGLTF_COMPONENT_TYPE_FLOAT;
}

std::unique_ptr<draco::Mesh> draco_mesh(const tinygltf::Model& model, const tinygltf::Value& e,
                                        const std::string& where) {
  const double index = member(e, "bufferView", where, 0, 1e9);
  if (index >= double(model.bufferViews.size()))
    throw InputError(where + ".bufferView", fmt::format("buffer view {} out of range", index));
  const tinygltf::BufferView& view = model.bufferViews[std::size_t(index)];
  const unsigned char* src =
      bytes_of(model, double(view.buffer), double(view.byteOffset), double(view.byteLength), where + ".bufferView");
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(src), view.byteLength);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) throw InputError(where, "Draco cannot decode it: " + decoded.status().error_msg_string());
  return std::move(decoded).value();
}

// Draco's faces as unsigned int indices.
std::vector<unsigned char> draco_indices(const draco::Mesh& mesh) {
  std::vector<std::uint32_t> idx;
  idx.reserve(3 * std::size_t(mesh.num_faces()));
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) idx.push_back(mesh.face(f)[k].value());
  std::vector<unsigned char> out(idx.size() * 4);
  std::memcpy(out.data(), idx.data(), out.size());
  return out;
}

// One attribute of every point, as floats (Draco dequantizes and normalizes).
std::vector<unsigned char> draco_floats(const draco::Mesh& mesh, const draco::PointAttribute& att,
                                        const std::string& where) {
  const int c = att.num_components();
  std::vector<float> v(std::size_t(mesh.num_points()) * std::size_t(c));
  for (draco::PointIndex i(0); i < mesh.num_points(); ++i)
    if (!att.ConvertValue<float>(att.mapped_index(i), std::int8_t(c), &v[std::size_t(i.value()) * std::size_t(c)]))
      throw InputError(where, "Draco cannot convert its values to floats");
  std::vector<unsigned char> out(v.size() * 4);
  std::memcpy(out.data(), v.data(), out.size());
  return out;
}

void decompress_draco(tinygltf::Model& model, tinygltf::Primitive& prim, const std::string& where) {
  const auto it = prim.extensions.find("KHR_draco_mesh_compression");
  if (it == prim.extensions.end()) return;
  const tinygltf::Value& e = it->second;
  const std::unique_ptr<draco::Mesh> mesh = draco_mesh(model, e, where);
  if (prim.indices < 0) {
    model.accessors.emplace_back();
    model.accessors.back().type = TINYGLTF_TYPE_SCALAR;
    prim.indices = int(model.accessors.size() - 1);
  }
  if (std::size_t(prim.indices) >= model.accessors.size())
    throw InputError(where + ".indices", fmt::format("accessor {} out of range", prim.indices));
  rewrite_accessor(model, model.accessors[std::size_t(prim.indices)], draco_indices(*mesh),
                   3 * std::size_t(mesh->num_faces()), 0);
  if (!e.Has("attributes") || !e.Get("attributes").IsObject()) throw InputError(where, "no attributes object");
  const tinygltf::Value& attributes = e.Get("attributes");
  for (const std::string& name : attributes.Keys()) {
    const std::string at = where + ".attributes." + name;
    const double id = member(attributes, name.c_str(), where + ".attributes", 0, 1e9);
    const auto accessor = prim.attributes.find(name);
    if (accessor == prim.attributes.end() || accessor->second < 0 ||
        std::size_t(accessor->second) >= model.accessors.size())
      throw InputError(at, "the primitive has no accessor for it");
    const draco::PointAttribute* att = mesh->GetAttributeByUniqueId(std::uint32_t(id));
    if (att == nullptr) throw InputError(at, fmt::format("the Draco data has no attribute {}", id));
    tinygltf::Accessor& a = model.accessors[std::size_t(accessor->second)];
    if (tinygltf::GetNumComponentsInType(std::uint32_t(a.type)) != att->num_components())
      throw InputError(at, fmt::format("{} components in the Draco data, {} in the accessor", att->num_components(),
                                       tinygltf::GetNumComponentsInType(std::uint32_t(a.type))));
    rewrite_accessor(model, a, draco_floats(*mesh, *att, at), std::size_t(mesh->num_points()), att->num_components());
  }
}

const char* const kCompression[] = {"KHR_draco_mesh_compression", "EXT_meshopt_compression"};

void drop_compression(std::vector<std::string>& extensions) {
  for (const char* name : kCompression)
    extensions.erase(std::remove(extensions.begin(), extensions.end(), name), extensions.end());
}

// Appends `bytes` to the merged buffer at an 8-byte boundary; returns where they start.
std::size_t append_aligned(std::vector<unsigned char>& merged, const std::vector<unsigned char>& bytes) {
  merged.resize((merged.size() + 7) / 8 * 8);
  const std::size_t at = merged.size();
  merged.insert(merged.end(), bytes.begin(), bytes.end());
  return at;
}

std::string image_mime(const std::vector<unsigned char>& bytes) {
  if (bytes.size() >= 4 && bytes[0] == 0x89 && bytes[1] == 'P' && bytes[2] == 'N' && bytes[3] == 'G')
    return "image/png";
  if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return "image/jpeg";
  return "";
}

}  // namespace

bool gltf_is_compressed(const tinygltf::Model& model) {
  for (const char* name : kCompression)
    if (std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), name) != model.extensionsUsed.end())
      return true;
  return false;
}

std::string plain_glb(tinygltf::Model model, const std::string& path) {
  std::vector<unsigned char> merged;
  std::vector<std::size_t> base;
  for (const tinygltf::Buffer& b : model.buffers) base.push_back(append_aligned(merged, b.data));
  for (std::size_t i = 0; i < model.bufferViews.size(); ++i) {
    tinygltf::BufferView& view = model.bufferViews[i];
    // tinygltf checks neither a view's buffer nor its range; the loader checks only the views it
    // reads, and the copy carries every view.
    if (view.buffer < 0 || std::size_t(view.buffer) >= base.size() ||
        view.byteOffset + view.byteLength > model.buffers[std::size_t(view.buffer)].data.size())
      throw InputError(fmt::format("{}: $.bufferViews[{}]", path, i), "lies outside its buffer");
    view.byteOffset += base[std::size_t(view.buffer)];
    view.buffer = 0;
    view.extensions.erase("EXT_meshopt_compression");
  }
  for (std::size_t i = 0; i < model.images.size(); ++i) {
    tinygltf::Image& image = model.images[i];
    if (image.bufferView >= 0) continue;
    const std::string mime = image_mime(image.image);
    if (mime.empty())
      throw InputError(fmt::format("{}: $.images[{}]", path, i),
                       "only PNG and JPEG images can be carried into Blender");
    tinygltf::BufferView view;
    view.byteOffset = append_aligned(merged, image.image);
    view.byteLength = image.image.size();
    model.bufferViews.push_back(view);
    image.bufferView = int(model.bufferViews.size() - 1);
    image.mimeType = mime;
    image.uri.clear();
  }
  model.buffers.assign(1, tinygltf::Buffer());
  model.buffers[0].data = std::move(merged);
  for (tinygltf::Mesh& mesh : model.meshes)
    for (tinygltf::Primitive& prim : mesh.primitives) prim.extensions.erase("KHR_draco_mesh_compression");
  drop_compression(model.extensionsUsed);
  drop_compression(model.extensionsRequired);
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, out, false, true)) throw InputError(path, "cannot be written as .glb");
  return out.str();
}

std::string gltf_prepared_for_tinygltf(std::string bytes, bool binary) {
  if (binary) return reprepare_glb(std::move(bytes));
  if (!mentions_compression(bytes)) return bytes;
  nlohmann::json doc = nlohmann::json::parse(bytes, nullptr, false);
  return prepare(doc) ? doc.dump() : bytes;
}

void decompress_gltf(tinygltf::Model& model, const std::string& path) {
  decompress_meshopt(model, path);
  for (std::size_t m = 0; m < model.meshes.size(); ++m)
    for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p)
      decompress_draco(
          model, model.meshes[m].primitives[p],
          fmt::format("{}: $.meshes[{}].primitives[{}].extensions.KHR_draco_mesh_compression", path, m, p));
}

}  // namespace insitu
