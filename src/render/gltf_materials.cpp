#include "render/gltf_materials.h"

#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

namespace insitu {
namespace fs = std::filesystem;
namespace {

// Decoded images by glTF index: a texture used twice is decoded once.
class GltfImages {
 public:
  GltfImages(const tinygltf::Model& model, std::string path) : model_(model), path_(std::move(path)) {}

  struct Decoded {
    std::shared_ptr<const Image> stored;  // as stored (k/255 for 8 bits), non-finite and negative values 0
    bool display_referred = false;        // integer pixels: sRGB-encoded where they are colour
  };

  // The image of texture `texture`, shared by every texture of the same source.
  const Decoded& get(int texture, const std::string& where) {
    if (texture < 0 || texture >= int(model_.textures.size()))
      throw InputError(where + ".index",
                       fmt::format("texture {} out of range ({} textures)", texture, model_.textures.size()));
    const int source = model_.textures[std::size_t(texture)].source;
    if (source < 0 || source >= int(model_.images.size()))
      throw InputError(fmt::format("{}: $.textures[{}].source", path_, texture),
                       source < 0 ? "no source image (an extension's image format insitu does not read)"
                                  : fmt::format("image {} out of range ({} images)", source, model_.images.size()));
    auto it = decoded_.find(source);
    if (it == decoded_.end()) it = decoded_.emplace(source, decode(source)).first;
    return it->second;
  }

 private:
  Decoded decode(int index) const {
    const tinygltf::Image& img = model_.images[std::size_t(index)];
    // JPEG by its first bytes (FF D8), whatever the mimeType or URI say or omit; else PNG.
    const bool jpeg = img.image.size() >= 2 && img.image[0] == 0xFF && img.image[1] == 0xD8;
    try {
      // The encoded bytes, kept by the loader (gltf_mesh.cpp), decoded by OpenImageIO.
      ImageFile file = read_image_memory(jpeg ? "embedded.jpg" : "embedded.png", img.image, PixelGrid::kAsStored);
      sanitize(file.stored);
      return {std::make_shared<const Image>(std::move(file.stored)), file.display_referred};
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: $.images[{}]", path_, index), e.message());
    }
  }

  const tinygltf::Model& model_;
  std::string path_;
  std::map<int, Decoded> decoded_;
};

// KHR_texture_transform's matrix on glTF's UVs, after F(u, v) = (u, 1 − v) (render/texture.h):
// T = translate(offset) · rotate(rotation) · scale(scale), with the extension's rotation matrix
// [cos sin; −sin cos].
Eigen::Matrix<float, 2, 3> image_from_uv(const tinygltf::Value& transform) {
  Eigen::Matrix3f t = Eigen::Matrix3f::Identity(), r = t, s = t, f = t;
  auto number = [&](const char* key, int i, float fallback) {
    if (!transform.Has(key)) return fallback;
    const tinygltf::Value& v = transform.Get(key);
    const tinygltf::Value& x = i < 0 ? v : v.Get(i);
    return x.IsNumber() ? float(x.GetNumberAsDouble()) : fallback;
  };
  t(0, 2) = number("offset", 0, 0), t(1, 2) = number("offset", 1, 0);
  const float rot = number("rotation", -1, 0);
  r << std::cos(rot), std::sin(rot), 0, -std::sin(rot), std::cos(rot), 0, 0, 0, 1;
  s(0, 0) = number("scale", 0, 1), s(1, 1) = number("scale", 1, 1);
  f(1, 1) = -1, f(1, 2) = 1;
  return (t * r * s * f).topRows<2>();
}

class MaterialReader {
 public:
  MaterialReader(const tinygltf::Model& model, const std::string& path, Warnings& warnings)
      : model_(model), path_(path), warnings_(warnings), images_(model, path) {}

  Material read(int index) {
    const tinygltf::Material& g = model_.materials[std::size_t(index)];
    const std::string where = fmt::format("{}: $.materials[{}]", path_, index);
    const auto& pbr = g.pbrMetallicRoughness;
    Material m;
    m.name = g.name.empty() ? fmt::format("material {}", index) : g.name;
    m.principled = true;
    for (int c = 0; c < 3; ++c) m.kd[c] = float(pbr.baseColorFactor[std::size_t(c)]);
    m.metallic = float(pbr.metallicFactor);
    m.roughness = float(pbr.roughnessFactor);
    if (!m.kd.allFinite() || (m.kd < 0).any() || !(m.metallic >= 0 && m.metallic <= 1) ||
        !(m.roughness >= 0 && m.roughness <= 1))
      throw InputError(where + ".pbrMetallicRoughness", "factors must be finite, within [0, 1]");
    m.map_kd = texture(pbr.baseColorTexture, true, where + ".pbrMetallicRoughness.baseColorTexture");
    m.map_metallic_roughness =
        texture(pbr.metallicRoughnessTexture, false, where + ".pbrMetallicRoughness.metallicRoughnessTexture");
    unrendered(g, m.name);
    return m;
  }

 private:
  Texture texture(const tinygltf::TextureInfo& info, bool srgb, const std::string& where) {
    Texture t;
    if (info.index < 0) return t;
    const auto& image = images_.get(info.index, where);
    t.image = image.stored;
    t.srgb = srgb && image.display_referred;  // data textures (metallic, roughness) are their stored values
    t.texcoord = info.texCoord;
    if (auto it = info.extensions.find("KHR_texture_transform"); it != info.extensions.end()) {
      t.image_from_uv = image_from_uv(it->second);
      if (it->second.Has("texCoord")) t.texcoord = it->second.Get("texCoord").GetNumberAsInt();
    } else {
      t.image_from_uv = image_from_uv(tinygltf::Value());
    }
    if (t.texcoord < 0 || t.texcoord > 1)
      throw InputError(where + ".texCoord", fmt::format("TEXCOORD_{}: insitu reads sets 0 and 1", t.texcoord));
    if (!t.image_from_uv.allFinite()) throw InputError(where, "KHR_texture_transform is not finite");
    const int sampler = model_.textures[std::size_t(info.index)].sampler;
    if (sampler >= 0 && sampler < int(model_.samplers.size())) {
      const auto& s = model_.samplers[std::size_t(sampler)];
      if (s.wrapS != TINYGLTF_TEXTURE_WRAP_REPEAT || s.wrapT != TINYGLTF_TEXTURE_WRAP_REPEAT)
        warnings_.add(where, "the sampler's wrap mode is not REPEAT; insitu repeats");
    }
    return t;
  }

  // What the material asks for that insitu does not render, named once per material.
  void unrendered(const tinygltf::Material& g, const std::string& name) {
    std::vector<std::string> what;
    if (g.emissiveTexture.index >= 0 || g.emissiveFactor[0] > 0 || g.emissiveFactor[1] > 0 || g.emissiveFactor[2] > 0)
      what.push_back("emission");
    if (g.alphaMode != "OPAQUE" && !g.alphaMode.empty()) what.push_back("alphaMode " + g.alphaMode);
    if (g.normalTexture.index >= 0) what.push_back("normalTexture");
    for (const auto& [ext, value] : g.extensions) what.push_back(ext);
    if (what.empty()) return;
    std::string list;
    for (const std::string& w : what) list += (list.empty() ? "" : ", ") + w;
    warnings_.add(fmt::format("{}: material '{}'", path_, name), "not rendered yet: " + list);
  }

  const tinygltf::Model& model_;
  const std::string& path_;
  Warnings& warnings_;
  GltfImages images_;
};

}  // namespace

std::vector<Material> gltf_materials(const tinygltf::Model& model, const std::string& path, Warnings& warnings) {
  MaterialReader reader(model, path, warnings);
  std::vector<Material> out;
  for (int i = 0; i < int(model.materials.size()); ++i) out.push_back(reader.read(i));
  Material fallback;  // glTF 2.0 §3.9.6: the default material
  fallback.name = "glTF default";
  fallback.principled = true;
  fallback.kd = Rgb::Ones();
  fallback.metallic = 1.0f;
  fallback.roughness = 1.0f;
  out.push_back(fallback);
  return out;
}

namespace {

// The JSON of a .gltf, or of a .glb's first chunk (12-byte header, then chunk length, "JSON").
nlohmann::json gltf_json(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  char magic[4] = {};
  in.read(magic, 4);
  if (std::memcmp(magic, "glTF", 4) != 0) {
    in.seekg(0);
    return nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  }
  std::uint32_t header[4] = {};  // version, length, chunk length, chunk type
  in.read(reinterpret_cast<char*>(header), sizeof(header));
  if (!in || header[3] != 0x4E4F534Au || header[2] > (1u << 30)) return {};
  std::string text(header[2], '\0');
  in.read(text.data(), std::streamsize(text.size()));
  return nlohmann::json::parse(text, nullptr, false);
}

}  // namespace

std::vector<std::string> gltf_dependencies(const std::string& path) {
  const nlohmann::json j = gltf_json(path);
  std::vector<std::string> files;
  if (!j.is_object()) return files;
  for (const char* list : {"buffers", "images"}) {
    if (!j.contains(list) || !j[list].is_array()) continue;
    for (const auto& item : j[list]) {
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = item["uri"];
      if (uri.rfind("data:", 0) == 0) continue;
      files.push_back((fs::path(path).parent_path() / uri).string());
    }
  }
  return files;
}

}  // namespace insitu
