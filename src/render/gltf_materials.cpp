#include "render/gltf_materials.h"

#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <set>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <exception>

namespace insitu {
namespace fs = std::filesystem;
namespace {

// Decoded images by glTF index: a texture used twice is decoded once.
class GltfImages {
 public:
  GltfImages(const tinygltf::Model& model, std::string path) : model_(model), path_(std::move(path)) {}

  struct Decoded {
    std::shared_ptr<const Texels> stored;  // as stored (k/255 for 8 bits), non-finite and negative values 0
    std::shared_ptr<const Texels> alpha;   // its alpha channel, or null
    bool display_referred = false;         // integer pixels: sRGB-encoded where they are colour
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
    if (auto failed = failed_.find(source); failed != failed_.end()) std::rethrow_exception(failed->second);
    auto it = decoded_.find(source);
    if (it == decoded_.end()) it = decoded_.emplace(source, decode(source)).first;
    return it->second;
  }

  // Decodes every image a texture names, side by side (a 4k PNG takes most of a second). An image
  // that fails keeps its error until get() asks for it, as if it were decoded then.
  void decode_named() {
    std::vector<int> sources;
    for (const tinygltf::Texture& t : model_.textures)
      if (t.source >= 0 && t.source < int(model_.images.size())) sources.push_back(t.source);
    std::sort(sources.begin(), sources.end());
    sources.erase(std::unique(sources.begin(), sources.end()), sources.end());
    std::vector<Decoded> images(sources.size());
    std::vector<std::exception_ptr> errors(sources.size());
    tbb::parallel_for(std::size_t(0), sources.size(), [&](std::size_t k) {
      try {
        images[k] = decode(sources[k]);
      } catch (...) {
        errors[k] = std::current_exception();
      }
    });
    for (std::size_t k = 0; k < sources.size(); ++k)
      errors[k] ? void(failed_.emplace(sources[k], errors[k]))
                : void(decoded_.emplace(sources[k], std::move(images[k])));
  }

 private:
  Decoded decode(int index) const {
    const tinygltf::Image& img = model_.images[std::size_t(index)];
    // JPEG by its first bytes (FF D8), whatever the mimeType or URI say or omit; else PNG.
    const bool jpeg = img.image.size() >= 2 && img.image[0] == 0xFF && img.image[1] == 0xD8;
    try {
      // The encoded bytes, kept by the loader (gltf_mesh.cpp), decoded by OpenImageIO.
      ImageFile file = read_texture_memory(jpeg ? "embedded.jpg" : "embedded.png", img.image, AlphaChannel::kKeep);
      return Decoded{texels_of(file), alpha_texels_of(file), file.display_referred};
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: $.images[{}]", path_, index), e.message());
    }
  }

  const tinygltf::Model& model_;
  std::string path_;
  std::map<int, Decoded> decoded_;
  std::map<int, std::exception_ptr> failed_;
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

  void decode_images() { images_.decode_named(); }

  Material read(int index) {
    const tinygltf::Material& g = model_.materials[std::size_t(index)];
    const std::string where = fmt::format("{}: $.materials[{}]", path_, index);
    const auto& pbr = g.pbrMetallicRoughness;
    Material m;
    m.name = g.name.empty() ? fmt::format("material {}", index) : g.name;
    m.principled = true;
    for (int c = 0; c < 3; ++c) m.kd[c] = float(pbr.baseColorFactor[std::size_t(c)]);
    m.alpha = float(pbr.baseColorFactor[3]);
    m.metallic = float(pbr.metallicFactor);
    m.roughness = float(pbr.roughnessFactor);
    if (!m.kd.allFinite() || (m.kd < 0).any() || !unit(m.alpha) || !unit(m.metallic) || !unit(m.roughness))
      throw InputError(where + ".pbrMetallicRoughness", "factors must be finite, within [0, 1]");
    m.map_kd = texture(pbr.baseColorTexture, true, where + ".pbrMetallicRoughness.baseColorTexture");
    m.map_metallic_roughness =
        texture(pbr.metallicRoughnessTexture, false, where + ".pbrMetallicRoughness.metallicRoughnessTexture");
    read_alpha(g, m, where);
    read_emission(g, m, where);
    read_normal(g, m, where);
    if (auto it = g.extensions.find("KHR_materials_clearcoat"); it != g.extensions.end())
      read_clearcoat(it->second, m, where + ".extensions.KHR_materials_clearcoat");
    if (auto it = g.extensions.find("KHR_materials_sheen"); it != g.extensions.end())
      read_sheen(it->second, m, where + ".extensions.KHR_materials_sheen");
    read_glass(g, m, where + ".extensions");
    if (auto it = g.extensions.find("KHR_materials_specular"); it != g.extensions.end())
      read_specular(it->second, m, where + ".extensions.KHR_materials_specular");
    unrendered(g, m.name);
    return m;
  }

 private:
  static bool unit(float x) { return x >= 0 && x <= 1; }

  // normalTexture: tangent-space, linear; its scale is the Normal Map node's strength, as Blender
  // 3.4's importer sets it (not glTF's scaling of x and y; render/shading_normal.h).
  void read_normal(const tinygltf::Material& g, Material& m, const std::string& where) {
    const tinygltf::NormalTextureInfo& n = g.normalTexture;
    if (n.index < 0) return;
    tinygltf::TextureInfo info;
    info.index = n.index;
    info.texCoord = n.texCoord;
    info.extensions = n.extensions;
    m.map_normal = texture(info, false, where + ".normalTexture");
    m.normal_strength = float(n.scale);
    if (!std::isfinite(m.normal_strength)) throw InputError(where + ".normalTexture.scale", "must be finite");
  }

  // KHR_materials_sheen as Blender 3.4's importer reads it: a Velvet BSDF of colour
  // sheenColorFactor × sheenColorTexture (sRGB) and σ = sheenRoughnessFactor × the alpha of
  // sheenRoughnessTexture, added to the principled one (render/bsdf.h).
  void read_sheen(const tinygltf::Value& ext, Material& m, const std::string& where) {
    if (ext.Has("sheenColorFactor")) m.sheen = unit_rgb(ext.Get("sheenColorFactor"), where + ".sheenColorFactor");
    m.sheen_roughness = number(ext, "sheenRoughnessFactor", 0.0f, where);
    if (!unit(m.sheen_roughness)) throw InputError(where + ".sheenRoughnessFactor", "must be within [0, 1]");
    m.map_sheen = texture(texture_info(ext, "sheenColorTexture"), true, where + ".sheenColorTexture");
    m.map_sheen_roughness =
        texture(texture_info(ext, "sheenRoughnessTexture"), false, where + ".sheenRoughnessTexture", true);
  }

  // Glass, as Blender 3.4's importer reads it (render/mesh.h): KHR_materials_transmission's factor
  // (× R of its texture) and KHR_materials_ior's index are the Principled BSDF's; where
  // KHR_materials_volume gives a thickness, the mesh holds a Volume Absorption of colour
  // attenuationColor and density 1/attenuationDistance (0 without one). Its thickness texture
  // shapes only a rasterizer's thin approximation, which neither Cycles nor insitu makes.
  void read_glass(const tinygltf::Material& g, Material& m, const std::string& where) {
    if (auto it = g.extensions.find("KHR_materials_transmission"); it != g.extensions.end()) {
      const std::string ext = where + ".KHR_materials_transmission";
      m.transmission = number(it->second, "transmissionFactor", 0.0f, ext);
      if (!unit(m.transmission)) throw InputError(ext + ".transmissionFactor", "must be within [0, 1]");
      m.map_transmission =
          texture(texture_info(it->second, "transmissionTexture"), false, ext + ".transmissionTexture");
    }
    if (auto it = g.extensions.find("KHR_materials_ior"); it != g.extensions.end()) {
      m.ior = number(it->second, "ior", 1.5f, where + ".KHR_materials_ior");
      if (!(m.ior >= 1 && m.ior <= 10)) throw InputError(where + ".KHR_materials_ior.ior", "must be within [1, 10]");
    }
    if (auto it = g.extensions.find("KHR_materials_volume"); it != g.extensions.end()) {
      const std::string ext = where + ".KHR_materials_volume";
      const float thickness = number(it->second, "thicknessFactor", 0.0f, ext);
      const float distance = number(it->second, "attenuationDistance", 0.0f, ext);
      if (!(thickness >= 0)) throw InputError(ext + ".thicknessFactor", "must be ≥ 0");
      if (it->second.Has("attenuationDistance") && !(distance > 0))
        throw InputError(ext + ".attenuationDistance", "must be > 0");
      Rgb colour = Rgb::Ones();
      if (it->second.Has("attenuationColor"))
        colour = unit_rgb(it->second.Get("attenuationColor"), ext + ".attenuationColor");
      if (thickness > 0 && distance > 0) m.absorption = (Rgb::Ones() - colour) / distance;
    }
  }

  // KHR_materials_specular (Material::specular_at, after the glass: it needs the transmission and
  // the index): its factor, colour and their textures, the colour's without its alpha (the alpha
  // is specularTexture's strength, which may share the image).
  void read_specular(const tinygltf::Value& ext, Material& m, const std::string& where) {
    m.specular_factor = number(ext, "specularFactor", 1.0f, where);
    if (!(m.specular_factor >= 0 && std::isfinite(m.specular_factor)))
      throw InputError(where + ".specularFactor", "must be a finite number ≥ 0");
    if (ext.Has("specularColorFactor")) {
      const tinygltf::Value& c = ext.Get("specularColorFactor");
      for (int k = 0; k < 3; ++k) {
        const double x = c.IsArray() && c.ArrayLen() == 3 && c.Get(k).IsNumber() ? c.Get(k).GetNumberAsDouble() : -1;
        if (!(x >= 0 && std::isfinite(x)))
          throw InputError(where + ".specularColorFactor", "must be 3 finite numbers ≥ 0");
        m.specular_colour[k] = float(x);
      }
    }
    m.has_specular_colour = true;
    m.specular = m.specular_at(UvSets{}, m.transmission);  // without the textures, read next
    m.map_specular = texture(texture_info(ext, "specularTexture"), false, where + ".specularTexture", true);
    m.map_specular_colour = texture(texture_info(ext, "specularColorTexture"), true, where + ".specularColorTexture");
    m.map_specular_colour.alpha = nullptr;
  }

  // Three numbers within [0, 1].
  static Rgb unit_rgb(const tinygltf::Value& c, const std::string& where) {
    Rgb out;
    for (int k = 0; k < 3; ++k) {
      const double x = c.IsArray() && c.ArrayLen() == 3 && c.Get(k).IsNumber() ? c.Get(k).GetNumberAsDouble() : -1;
      if (!(x >= 0 && x <= 1)) throw InputError(where, "must be 3 numbers within [0, 1]");
      out[k] = float(x);
    }
    return out;
  }

  // A number of an extension's object, or `fallback`; a value that is not a finite number is refused.
  static float number(const tinygltf::Value& object, const char* key, float fallback, const std::string& where) {
    if (!object.Has(key)) return fallback;
    const tinygltf::Value& v = object.Get(key);
    const double x = v.IsNumber() ? v.GetNumberAsDouble() : std::nan("");
    if (!std::isfinite(x)) throw InputError(where + "." + key, "must be a finite number");
    return float(x);
  }

  // An extension's textureInfo object, as tinygltf reads the core ones.
  static tinygltf::TextureInfo texture_info(const tinygltf::Value& object, const char* key) {
    tinygltf::TextureInfo info;
    if (!object.Has(key)) return info;
    const tinygltf::Value& v = object.Get(key);
    if (v.Has("index") && v.Get("index").IsInt()) info.index = v.Get("index").GetNumberAsInt();
    if (v.Has("texCoord") && v.Get("texCoord").IsInt()) info.texCoord = v.Get("texCoord").GetNumberAsInt();
    if (v.Has("extensions") && v.Get("extensions").Has("KHR_texture_transform"))
      info.extensions["KHR_texture_transform"] = v.Get("extensions").Get("KHR_texture_transform");
    return info;
  }

  // alphaMode and alphaCutoff (glTF 2.0 §3.9.4); the base colour texture's alpha channel.
  void read_alpha(const tinygltf::Material& g, Material& m, const std::string& where) {
    if (g.alphaMode == "MASK") {
      m.alpha_mode = Material::AlphaMode::kMask;
    } else if (g.alphaMode == "BLEND") {
      m.alpha_mode = Material::AlphaMode::kBlend;
    } else if (!g.alphaMode.empty() && g.alphaMode != "OPAQUE") {
      throw InputError(where + ".alphaMode", fmt::format("'{}' is not OPAQUE, MASK or BLEND", g.alphaMode));
    }
    m.alpha_cutoff = float(g.alphaCutoff);
    if (!(m.alpha_cutoff >= 0) || !std::isfinite(m.alpha_cutoff))
      throw InputError(where + ".alphaCutoff", "must be a finite number ≥ 0");
  }

  // emissiveFactor × emissiveTexture (sRGB) × KHR_materials_emissive_strength.
  void read_emission(const tinygltf::Material& g, Material& m, const std::string& where) {
    for (int c = 0; c < 3; ++c) m.emission[c] = float(g.emissiveFactor[std::size_t(c)]);
    if (!m.emission.allFinite() || (m.emission < 0).any() || (m.emission > 1).any())
      throw InputError(where + ".emissiveFactor", "must be finite, within [0, 1]");
    m.map_emission = texture(g.emissiveTexture, true, where + ".emissiveTexture");
    if (auto it = g.extensions.find("KHR_materials_emissive_strength"); it != g.extensions.end()) {
      const std::string ext = where + ".extensions.KHR_materials_emissive_strength";
      const float strength = number(it->second, "emissiveStrength", 1.0f, ext);
      if (strength < 0) throw InputError(ext + ".emissiveStrength", "must be ≥ 0");
      m.emission *= strength;
    }
  }

  // KHR_materials_clearcoat: the coat's factor (× R) and roughness (× G), and its own normal map,
  // whose `scale` is the Normal Map node's strength as for normalTexture (Blender's Clearcoat
  // Normal). The tangents are those of one UV set per material (Material::tangent_map): a coat map
  // on another set than the normal map's is read with the normal map's tangents, and warned.
  void read_clearcoat(const tinygltf::Value& ext, Material& m, const std::string& where) {
    m.clearcoat = number(ext, "clearcoatFactor", 0.0f, where);
    m.clearcoat_roughness = number(ext, "clearcoatRoughnessFactor", 0.0f, where);
    if (!unit(m.clearcoat) || !unit(m.clearcoat_roughness))
      throw InputError(where, "clearcoatFactor and clearcoatRoughnessFactor must be within [0, 1]");
    m.map_clearcoat = texture(texture_info(ext, "clearcoatTexture"), false, where + ".clearcoatTexture");
    m.map_clearcoat_roughness =
        texture(texture_info(ext, "clearcoatRoughnessTexture"), false, where + ".clearcoatRoughnessTexture");
    const std::string normal_where = where + ".clearcoatNormalTexture";
    m.map_clearcoat_normal = texture(texture_info(ext, "clearcoatNormalTexture"), false, normal_where);
    if (!m.map_clearcoat_normal) return;
    m.clearcoat_normal_strength = number(ext.Get("clearcoatNormalTexture"), "scale", 1.0f, normal_where);
    if (m.map_normal && m.map_normal.texcoord != m.map_clearcoat_normal.texcoord)
      warnings_.add(normal_where, fmt::format("on TEXCOORD_{}, the normal map on TEXCOORD_{}: insitu bends it along "
                                              "the normal map's tangents",
                                              m.map_clearcoat_normal.texcoord, m.map_normal.texcoord));
  }

  // A texture; its alpha channel is kept for colour textures (the base colour's opacity) and where
  // asked for (`alpha`: a value stored in alpha).
  Texture texture(const tinygltf::TextureInfo& info, bool srgb, const std::string& where, bool alpha = false) {
    Texture t;
    if (info.index < 0) return t;
    const auto& image = images_.get(info.index, where);
    t.image = image.stored;
    if (srgb || alpha) t.alpha = image.alpha;
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
    static const std::set<std::string> kRead = {"KHR_materials_clearcoat", "KHR_materials_emissive_strength",
                                                "KHR_materials_sheen",     "KHR_materials_transmission",
                                                "KHR_materials_ior",       "KHR_materials_volume",
                                                "KHR_materials_specular"};
    std::vector<std::string> what;
    for (const auto& [ext, value] : g.extensions)
      if (!kRead.count(ext)) what.push_back(ext);
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
  if (!model.materials.empty()) reader.decode_images();
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
