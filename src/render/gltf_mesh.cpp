#include "render/gltf_mesh.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fmt/format.h>
#include <cstring>
#include <fstream>
#include <set>

#include "core/file_check.h"
#include "render/gltf_decompress.h"
#include "render/gltf_materials.h"
#include "render/tangents.h"

namespace insitu {
namespace fs = std::filesystem;
namespace {

// Extensions a file may require that insitu renders as the file means them.
const std::set<std::string> kSupportedRequired = {"KHR_texture_transform", "KHR_draco_mesh_compression",
                                                  "EXT_meshopt_compression", "KHR_mesh_quantization"};

// tinygltf's image hook: keep the encoded bytes, decoded later by OpenImageIO (gltf_materials.cpp)
// with insitu's checks on size and corruption.
bool keep_encoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
                  int size, void*) {
  image->image.assign(bytes, bytes + std::max(0, size));
  image->as_is = true;
  return true;
}

std::string first_line(const std::string& s) {
  const std::string line = s.substr(0, s.find('\n'));
  return line.empty() ? "cannot be parsed" : line;
}

// The whole file, refused beyond tinygltf's 4 GiB (its lengths are unsigned int).
std::string file_bytes(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw InputError(path, "cannot be read: " + ec.message());
  if (size == 0) throw InputError(path, "is empty");
  if (size >= (std::uintmax_t(1) << 32)) throw InputError(path, "is larger than 4 GiB");
  std::string bytes(size, '\0');
  std::ifstream in(path, std::ios::binary);
  if (!in.read(bytes.data(), std::streamsize(size))) throw InputError(path, "cannot be read");
  return bytes;
}

// GLB (glTF 2.0 §4.4): a 12-byte header, the JSON chunk, then an optional BIN chunk of (length,
// type, bytes). tinygltf 2.7 bounds the BIN chunk's length by the file less its header and JSON
// chunk, forgetting the BIN chunk's own 8-byte header, and so copies up to 8 bytes past the end of
// the file (fuzz_gltf found it). The chunk must lie within both the file and its declared length.
void check_glb_bin_chunk(const std::string& bytes, const std::string& path) {
  auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    if (at + 4 <= bytes.size()) std::memcpy(&v, bytes.data() + at, 4);
    return std::uint64_t(v);
  };
  const std::uint64_t declared = std::min<std::uint64_t>(u32(8), bytes.size());
  const std::uint64_t bin_at = 20 + u32(12);
  if (bin_at + 8 > declared) return;  // no BIN chunk, or one tinygltf refuses itself
  const std::uint64_t bin_length = u32(bin_at);
  if (bin_at + 8 + bin_length > declared)
    throw InputError(
        fmt::format("{}: byte {}", path, bin_at),
        fmt::format("the BIN chunk declares {} bytes, but {} follow its header", bin_length, declared - bin_at - 8));
}

tinygltf::Model parse(const std::string& path, Warnings& warnings) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keep_encoded, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  const bool binary = ext == ".glb";
  std::string bytes = file_bytes(path);
  if (binary) check_glb_bin_chunk(bytes, path);
  bytes = gltf_prepared_for_tinygltf(std::move(bytes), binary);
  if (binary) check_glb_bin_chunk(bytes, path);  // its JSON chunk rewritten, the BIN chunk moves
  const std::string dir = fs::path(path).parent_path().string();
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                           unsigned(bytes.size()), dir)
             : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), dir);
  if (!ok || !err.empty()) throw InputError(path, first_line(err));
  if (!warn.empty()) warnings.add(path, first_line(warn));
  for (std::size_t i = 0; i < model.extensionsRequired.size(); ++i)
    if (!kSupportedRequired.count(model.extensionsRequired[i]))
      throw InputError(fmt::format("{}: $.extensionsRequired[{}]", path, i),
                       fmt::format("the file requires {}, which insitu does not support", model.extensionsRequired[i]));
  decompress_gltf(model, path);
  return model;
}

// Reads accessors with their bounds checked against their buffer view and buffer.
class Accessors {
 public:
  Accessors(const tinygltf::Model& model, const std::string& path) : model_(model), path_(path) {}

  // `components` floats per element: float, or normalized unsigned byte or short.
  std::vector<float> floats(int index, int components, const char* semantic) const {
    const tinygltf::Accessor& a = checked(index, semantic, components);
    const int ct = a.componentType;
    if (ct != TINYGLTF_COMPONENT_TYPE_FLOAT && ct != TINYGLTF_COMPONENT_TYPE_BYTE &&
        ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_SHORT &&
        ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)
      throw InputError(where(index, semantic), "component type must be float, or a byte or short");
    std::vector<float> out(a.count * std::size_t(components));
    for_each(a, [&](std::size_t i, const unsigned char* p) {
      for (int c = 0; c < components; ++c) out[i * components + c] = component(p, ct, a.normalized, c);
    });
    for (float v : out)
      if (!std::isfinite(v)) throw InputError(where(index, semantic), "a value is not finite");
    return out;
  }

  std::vector<std::uint32_t> indices(int index) const {
    const tinygltf::Accessor& a = checked(index, "indices", 1);
    const int ct = a.componentType;
    if (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      throw InputError(where(index, "indices"), "component type must be unsigned byte, short or int");
    std::vector<std::uint32_t> out(a.count);
    for_each(a, [&](std::size_t i, const unsigned char* p) {
      if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) out[i] = *p;
      if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) out[i] = read<std::uint16_t>(p);
      if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) out[i] = read<std::uint32_t>(p);
    });
    return out;
  }

  std::string where(int index, const char* semantic) const {
    return fmt::format("{}: $.accessors[{}] ({})", path_, index, semantic);
  }

 private:
  template <class T>
  static T read(const unsigned char* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
  }
  // glTF's integer components (KHR_mesh_quantization): normalized, unsigned c / (2ᵇ − 1) and signed
  // max(c / (2ᵇ⁻¹ − 1), −1) (glTF 2.0, "Animation samplers" and the extension's table); else c.
  static float component(const unsigned char* p, int ct, bool normalized, int c) {
    switch (ct) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return read<float>(p + 4 * c);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return integer(p[c], 255, normalized);
      case TINYGLTF_COMPONENT_TYPE_BYTE:
        return integer(read<std::int8_t>(p + c), 127, normalized);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return integer(read<std::uint16_t>(p + 2 * c), 65535, normalized);
      default:
        return integer(read<std::int16_t>(p + 2 * c), 32767, normalized);
    }
  }
  static float integer(int value, float max, bool normalized) {
    return normalized ? std::max(float(value) / max, -1.0f) : float(value);
  }

  // The accessor, its type (SCALAR, VEC2, VEC3 by `components`) and its bytes within its view and buffer.
  const tinygltf::Accessor& checked(int index, const char* semantic, int components) const {
    if (index < 0 || index >= int(model_.accessors.size()))
      throw InputError(fmt::format("{}: {}", path_, semantic),
                       fmt::format("accessor {} out of range ({} accessors)", index, model_.accessors.size()));
    const tinygltf::Accessor& a = model_.accessors[std::size_t(index)];
    if (tinygltf::GetNumComponentsInType(std::uint32_t(a.type)) != components)
      throw InputError(where(index, semantic), fmt::format("expected {} components per element", components));
    if (a.count == 0) throw InputError(where(index, semantic), "no elements");
    const int component_size = tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType));
    if (component_size <= 0) throw InputError(where(index, semantic), "an unknown component type");
    const std::uint64_t element = std::uint64_t(component_size) * std::uint64_t(components);
    if (a.bufferView >= 0 || !a.sparse.isSparse) {  // glTF: without a view, the elements are zeros
      const tinygltf::BufferView& view = checked_view(a.bufferView, where(index, semantic));
      const int stride = a.ByteStride(view);
      if (stride <= 0) throw InputError(where(index, semantic), "a bad stride");
      if (a.count > view.byteLength) throw InputError(where(index, semantic), "more elements than its view has bytes");
      in_view(view, a.byteOffset, std::uint64_t(stride) * (a.count - 1) + element, where(index, semantic));
    }
    // Without a view nothing bounds the count but this (memory stays bounded; 16.7 M elements is
    // far beyond any piece of furniture).
    constexpr std::size_t kMaxViewless = std::size_t(1) << 24;
    if (a.bufferView < 0 && a.count > kMaxViewless)
      throw InputError(where(index, semantic),
                       fmt::format("{} elements without a buffer view (at most {})", a.count, kMaxViewless));
    if (a.sparse.isSparse) check_sparse(a, element, fmt::format("{}: $.accessors[{}].sparse", path_, index));
    return a;
  }

  const tinygltf::BufferView& checked_view(int view_index, const std::string& where) const {
    if (view_index < 0 || view_index >= int(model_.bufferViews.size()))
      throw InputError(where, "no buffer view holds its data");
    const tinygltf::BufferView& view = model_.bufferViews[std::size_t(view_index)];
    if (view.buffer < 0 || view.buffer >= int(model_.buffers.size()))
      throw InputError(where, fmt::format("buffer view {} names no buffer", view_index));
    return view;
  }

  // `bytes` from `offset` lie within the view, and the view within its buffer.
  void in_view(const tinygltf::BufferView& view, std::uint64_t offset, std::uint64_t bytes,
               const std::string& where) const {
    const std::uint64_t length = view.byteLength, buffer = model_.buffers[std::size_t(view.buffer)].data.size();
    if (offset > length || bytes > length - offset || view.byteOffset > buffer || length > buffer - view.byteOffset)
      throw InputError(where, "its data runs past the end of its buffer view or buffer");
  }

  // glTF 2.0 §3.6.2.3: `count` indices (unsigned byte, short or int), strictly increasing and below
  // the accessor's count, and as many values of the accessor's element, tightly packed.
  void check_sparse(const tinygltf::Accessor& a, std::uint64_t element, const std::string& where) const {
    const auto& sp = a.sparse;
    const int ct = sp.indices.componentType;
    if (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      throw InputError(where + ".indices", "component type must be unsigned byte, short or int");
    if (sp.count < 1 || std::size_t(sp.count) > a.count)
      throw InputError(where + ".count", fmt::format("{} is not within [1, {}]", sp.count, a.count));
    if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0) throw InputError(where, "a negative byteOffset");
    const auto n = std::uint64_t(sp.count);
    const std::uint64_t index_size = tinygltf::GetComponentSizeInBytes(std::uint32_t(ct));
    in_view(checked_view(sp.indices.bufferView, where + ".indices"), std::uint64_t(sp.indices.byteOffset),
            n * index_size, where + ".indices");
    in_view(checked_view(sp.values.bufferView, where + ".values"), std::uint64_t(sp.values.byteOffset), n * element,
            where + ".values");
    const std::vector<std::uint32_t> at = sparse_indices(a);
    for (std::size_t k = 0; k < at.size(); ++k)
      if (at[k] >= a.count || (k > 0 && at[k] <= at[k - 1]))
        throw InputError(where + ".indices", fmt::format("index {} at {} is out of range or not increasing", at[k], k));
  }

  std::vector<std::uint32_t> sparse_indices(const tinygltf::Accessor& a) const {
    const auto& ix = a.sparse.indices;
    const unsigned char* p = view_bytes(ix.bufferView) + ix.byteOffset;
    std::vector<std::uint32_t> out(std::size_t(a.sparse.count));
    for (std::size_t k = 0; k < out.size(); ++k) {
      if (ix.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) out[k] = p[k];
      if (ix.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) out[k] = read<std::uint16_t>(p + 2 * k);
      if (ix.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) out[k] = read<std::uint32_t>(p + 4 * k);
    }
    return out;
  }

  const unsigned char* view_bytes(int view_index) const {
    const tinygltf::BufferView& view = model_.bufferViews[std::size_t(view_index)];
    return model_.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset;
  }

  // f(i, element i's bytes) for every element: the view's, or zeros without one, and a sparse
  // accessor's values at its indices.
  template <class F>
  void for_each(const tinygltf::Accessor& a, F&& f) const {
    static const unsigned char kZeros[64] = {};  // the largest element read here: 4 floats
    const bool viewed = a.bufferView >= 0;
    const unsigned char* base = viewed ? view_bytes(a.bufferView) + a.byteOffset : kZeros;
    const std::size_t stride = viewed ? std::size_t(a.ByteStride(model_.bufferViews[std::size_t(a.bufferView)])) : 0;
    std::vector<std::uint32_t> at;
    const unsigned char* values = nullptr;
    std::size_t element = 0;
    if (a.sparse.isSparse) {
      at = sparse_indices(a);
      values = view_bytes(a.sparse.values.bufferView) + a.sparse.values.byteOffset;
      element = std::size_t(tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType))) *
                std::size_t(tinygltf::GetNumComponentsInType(std::uint32_t(a.type)));
    }
    std::size_t k = 0;  // the next sparse entry
    for (std::size_t i = 0; i < a.count; ++i) {
      if (k < at.size() && at[k] == i)
        f(i, values + element * k++);
      else
        f(i, base + i * stride);
    }
  }

  const tinygltf::Model& model_;
  const std::string& path_;
};

// A node's own transform: its matrix (column-major), or T · R · S.
Mat4d local_transform(const tinygltf::Node& node) {
  Mat4d m = Mat4d::Identity();
  if (node.matrix.size() == 16) {
    for (int i = 0; i < 16; ++i) m(i % 4, i / 4) = node.matrix[std::size_t(i)];
    return m;
  }
  if (node.scale.size() == 3) m.topLeftCorner<3, 3>() = Vec3d(node.scale[0], node.scale[1], node.scale[2]).asDiagonal();
  if (node.rotation.size() == 4) {
    const Eigen::Quaterniond q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    m.topLeftCorner<3, 3>() = q.normalized().toRotationMatrix() * m.topLeftCorner<3, 3>();
  }
  if (node.translation.size() == 3)
    m.topRightCorner<3, 1>() = Vec3d(node.translation[0], node.translation[1], node.translation[2]);
  return m;
}

class MeshBuilder {
 public:
  static constexpr int kMaxDepth = 1000;
  MeshBuilder(const tinygltf::Model& model, const std::string& path, Warnings& warnings)
      : model_(model), path_(path), warnings_(warnings), accessors_(model, path) {
    for (const auto& mesh : model.meshes)
      for (const auto& prim : mesh.primitives) {
        uv0_ |= prim.attributes.count("TEXCOORD_0") > 0;
        uv1_ |= prim.attributes.count("TEXCOORD_1") > 0;
      }
    out_.source = path;
    out_.files.push_back(path);
    out_.materials = gltf_materials(model, path, warnings);
  }

  // A node and its subtree; `depth` bounds the recursion (a chain of nodes as deep as the file is long).
  void node(int index, const Mat4d& parent, std::vector<char>& visited, int depth = 0) {
    if (depth > kMaxDepth)
      throw InputError(fmt::format("{}: $.nodes[{}]", path_, index),
                       fmt::format("nested deeper than {} levels", kMaxDepth));
    if (index < 0 || index >= int(model_.nodes.size()))
      throw InputError(fmt::format("{}: $.nodes", path_), fmt::format("node {} out of range", index));
    if (visited[std::size_t(index)])
      throw InputError(fmt::format("{}: $.nodes[{}]", path_, index),
                       "the node hierarchy is not a tree (a cycle, or two parents)");
    visited[std::size_t(index)] = 1;
    const tinygltf::Node& n = model_.nodes[std::size_t(index)];
    const Mat4d world = parent * local_transform(n);
    if (!world.allFinite())
      throw InputError(fmt::format("{}: $.nodes[{}]", path_, index), "its transform is not finite");
    if (n.mesh >= int(model_.meshes.size()))
      throw InputError(fmt::format("{}: $.nodes[{}].mesh", path_, index), fmt::format("mesh {} out of range", n.mesh));
    if (n.mesh >= 0)
      for (std::size_t p = 0; p < model_.meshes[std::size_t(n.mesh)].primitives.size(); ++p)
        primitive(n.mesh, p, world);
    for (int child : n.children) node(child, world, visited, depth + 1);
  }

  Mesh finish() {
    if (out_.triangles.empty()) throw InputError(path_, "the default scene holds no triangles");
    if (dropped_ > 0) warnings_.add(path_, fmt::format("{} degenerate triangles dropped", dropped_));
    tangents();
    if (!uses_default_) out_.materials.pop_back();
    return std::move(out_);
  }

 private:
  void primitive(int mesh, std::size_t p, const Mat4d& world) {
    const tinygltf::Primitive& prim = model_.meshes[std::size_t(mesh)].primitives[p];
    const std::string where = fmt::format("{}: $.meshes[{}].primitives[{}]", path_, mesh, p);
    if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) {
      warnings_.add(where, fmt::format("mode {} skipped: insitu renders triangles (mode 4)", prim.mode));
      return;
    }
    const auto attribute = [&](const char* name) {
      const auto it = prim.attributes.find(name);
      return it == prim.attributes.end() ? -1 : it->second;
    };
    if (attribute("POSITION") < 0) throw InputError(where, "no POSITION attribute");
    const std::vector<float> pos = accessors_.floats(attribute("POSITION"), 3, "POSITION");
    const std::size_t n = pos.size() / 3, base = out_.positions.size();
    const Eigen::Matrix3d normal_matrix = world.topLeftCorner<3, 3>().inverse().transpose();
    for (std::size_t i = 0; i < n; ++i)
      out_.positions.push_back(
          (world * Eigen::Vector4d(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2], 1)).head<3>().cast<float>());
    const bool normals = attribute("NORMAL") >= 0;
    if (normals) {
      const std::vector<float> nor = vertex_floats(attribute("NORMAL"), 3, "NORMAL", n);
      for (std::size_t i = 0; i < n; ++i) {
        const Vec3d v = normal_matrix * Vec3d(nor[3 * i], nor[3 * i + 1], nor[3 * i + 2]);
        out_.normals.push_back((v.norm() > 0 ? v.normalized() : v).cast<float>());
      }
    }
    file_tangents(attribute("TANGENT"), n, world.topLeftCorner<3, 3>());
    uvs(attribute("TEXCOORD_0"), "TEXCOORD_0", n, uv0_, out_.uvs);
    uvs(attribute("TEXCOORD_1"), "TEXCOORD_1", n, uv1_, out_.uvs1);
    int material = prim.material;
    if (material < -1 || material >= int(model_.materials.size()))
      throw InputError(where + ".material", fmt::format("material {} out of range", material));
    if (material < 0) {
      material = int(out_.materials.size()) - 1;  // glTF's default material
      uses_default_ = true;
    }
    triangles(prim, where, n, base, normals ? std::int64_t(out_.normals.size() - n) : -1, material);
  }

  std::vector<float> vertex_floats(int accessor, int components, const char* semantic, std::size_t n) const {
    std::vector<float> v = accessors_.floats(accessor, components, semantic);
    if (v.size() != n * std::size_t(components))
      throw InputError(accessors_.where(accessor, semantic),
                       fmt::format("{} elements for {} positions", v.size() / components, n));
    return v;
  }

  // TANGENT (xyz, and w = ±1 the bitangent's sign), to world like transform_mesh; w = 0 where the
  // primitive has none.
  void file_tangents(int accessor, std::size_t n, const Eigen::Matrix3d& linear) {
    if (accessor < 0) {
      file_tangents_.insert(file_tangents_.end(), n, Vec4f::Zero());
      return;
    }
    const std::vector<float> t = vertex_floats(accessor, 4, "TANGENT", n);
    const float handedness = linear.determinant() < 0 ? -1.0f : 1.0f;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3d v = linear * Vec3d(t[4 * i], t[4 * i + 1], t[4 * i + 2]);
      Vec4f tangent = Vec4f::Zero();
      if (v.norm() > 0) tangent << v.normalized().cast<float>(), t[4 * i + 3] < 0 ? -handedness : handedness;
      file_tangents_.push_back(tangent);
    }
  }

  // The tangents of the normal maps' UV sets (render/tangents.h, Material::tangent_map), where some
  // material has a normal map: the file's TANGENT where a triangle's three vertices have it, MikkTSpace's elsewhere.
  void tangents() {
    std::array<std::vector<Vec4f>, 2> generated;
    for (std::size_t f = 0; f < out_.triangles.size(); ++f) {
      const Triangle& tri = out_.triangles[f];
      const Texture& map = out_.materials[std::size_t(tri.material)].tangent_map();
      if (!map) continue;
      if (out_.tangents.empty()) out_.tangents.assign(3 * out_.triangles.size(), Vec4f(1, 0, 0, 1));
      const bool in_file =
          std::all_of(tri.v.begin(), tri.v.end(), [&](std::uint32_t v) { return file_tangents_[v].w() != 0; });
      std::vector<Vec4f>& gen = generated[std::size_t(map.texcoord)];
      if (!in_file && gen.empty()) gen = mikktspace_tangents(out_, map.texcoord);
      for (std::size_t k = 0; k < 3; ++k)
        out_.tangents[3 * f + k] = in_file ? file_tangents_[tri.v[k]] : gen[3 * f + k];
    }
  }

  // A UV set: present in some primitive, it is stored for every vertex (zero where a primitive lacks it).
  void uvs(int accessor, const char* semantic, std::size_t n, bool any, std::vector<Vec2f>& out) const {
    if (!any) return;
    if (accessor < 0) {
      out.insert(out.end(), n, Vec2f::Zero());
      return;
    }
    const std::vector<float> uv = vertex_floats(accessor, 2, semantic, n);
    for (std::size_t i = 0; i < n; ++i) out.emplace_back(uv[2 * i], 1.0f - uv[2 * i + 1]);
  }

  void triangles(const tinygltf::Primitive& prim, const std::string& where, std::size_t n, std::size_t base,
                 std::int64_t normal_base, int material) {
    std::vector<std::uint32_t> idx;
    if (prim.indices >= 0) {
      idx = accessors_.indices(prim.indices);
    } else {
      idx.resize(n);
      for (std::size_t i = 0; i < n; ++i) idx[i] = std::uint32_t(i);
    }
    if (idx.size() % 3 != 0) throw InputError(where, fmt::format("{} indices: not a multiple of 3", idx.size()));
    for (std::size_t i = 0; i < idx.size(); ++i)
      if (idx[i] >= n)
        throw InputError(accessors_.where(prim.indices, "indices"),
                         fmt::format("index {} at {} out of range ({} vertices)", idx[i], i, n));
    for (std::size_t i = 0; i < idx.size(); i += 3) {
      Triangle t{};
      for (int k = 0; k < 3; ++k) {
        t.v[std::size_t(k)] = std::uint32_t(base + idx[i + std::size_t(k)]);
        t.n[std::size_t(k)] = normal_base >= 0 ? std::int32_t(normal_base + idx[i + std::size_t(k)]) : -1;
        t.t[std::size_t(k)] = uv0_ || uv1_ ? std::int32_t(t.v[std::size_t(k)]) : -1;
      }
      t.material = material;
      if (degenerate_triangle(out_, t)) {
        ++dropped_;
        continue;
      }
      out_.triangles.push_back(t);
    }
  }

  const tinygltf::Model& model_;
  const std::string& path_;
  Warnings& warnings_;
  Accessors accessors_;
  bool uv0_ = false, uv1_ = false, uses_default_ = false;
  std::size_t dropped_ = 0;
  std::vector<Vec4f> file_tangents_;  // per position
  Mesh out_;
};

}  // namespace

bool is_gltf_path(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".gltf" || ext == ".glb";
}

Mesh load_gltf(const std::string& path, Warnings& warnings) {
  require_existing(path);
  const tinygltf::Model model = parse(path, warnings);
  MeshBuilder builder(model, path, warnings);
  std::vector<char> visited(model.nodes.size(), 0);
  std::vector<int> roots;
  if (!model.scenes.empty()) {
    const int scene = model.defaultScene >= 0 && model.defaultScene < int(model.scenes.size()) ? model.defaultScene : 0;
    roots = model.scenes[std::size_t(scene)].nodes;
  } else {  // no scene: every node that is nobody's child
    std::vector<char> child(model.nodes.size(), 0);
    for (const auto& node : model.nodes)
      for (int c : node.children)
        if (c >= 0 && c < int(child.size())) child[std::size_t(c)] = 1;
    for (std::size_t i = 0; i < child.size(); ++i)
      if (!child[i]) roots.push_back(int(i));
  }
  for (int root : roots) builder.node(root, Mat4d::Identity(), visited);
  Mesh mesh = builder.finish();
  for (std::string& file : gltf_dependencies(path)) mesh.files.push_back(std::move(file));
  return mesh;
}

std::optional<std::string> gltf_plain_copy(const std::string& path) {
  Warnings ignored;  // load_gltf reported them
  const tinygltf::Model model = parse(path, ignored);
  if (!gltf_is_compressed(model)) return std::nullopt;
  return plain_glb(model, path);
}

Mesh load_mesh(const std::string& path, Warnings& warnings) {
  return is_gltf_path(path) ? load_gltf(path, warnings) : load_obj(path, warnings);
}

std::vector<std::string> mesh_dependencies(const std::string& path) {
  return is_gltf_path(path) ? gltf_dependencies(path) : obj_dependencies(path);
}

}  // namespace insitu
