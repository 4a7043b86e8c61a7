#include "demo_chair.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <tiny_gltf.h>
#include <vector>

#include "core/colour.h"
#include "core/image.h"
#include "core/math.h"
#include "core/sampler.h"

namespace insitu {
namespace {
namespace fs = std::filesystem;

// One primitive's vertices (glTF's UVs, v down) and triangles.
struct Part {
  std::vector<float> pos, nor, uv;
  std::vector<std::uint32_t> idx;
};

// The grid coordinates along one side of a box face, from −h to h: `steps` segments across each
// rounded edge of radius r and one across the flat middle (none where r = h).
std::vector<float> edge_grid(float h, float r, int steps) {
  std::vector<float> s;
  for (int k = 0; k <= steps; ++k) s.push_back(-h + r * float(k) / float(steps));
  for (int k = steps; k >= 0; --k) s.push_back(h - r * float(k) / float(steps));
  s.erase(std::unique(s.begin(), s.end(), [](float a, float b) { return std::abs(a - b) < 1e-6f; }), s.end());
  return s;
}

// A box of half sizes h about c with every edge rounded to radius r: each face's grid point p is
// moved onto the rounded box, p' = q + r (p − q)/|p − q| with q = clamp(p, −(h − r), h − r), and
// its normal is (p − q)/|p − q|. UVs are the face's own two coordinates over `repeat_m` metres,
// u along the face's longer side (the grain runs along a part, walnut_ring).
void rounded_box(Part& part, const Vec3f& c, const Vec3f& h, float r, float repeat_m) {
  const Vec3f inner = h - Vec3f::Constant(r);
  for (int a = 0; a < 3; ++a)
    for (float sign : {1.0f, -1.0f}) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      const std::vector<float> su = edge_grid(h[u], r, 4), sv = edge_grid(h[v], r, 4);
      const auto base = std::uint32_t(part.pos.size() / 3);
      for (float y : sv)
        for (float x : su) {
          Vec3f p;
          p[a] = sign * h[a], p[u] = x, p[v] = y;
          const Vec3f q = p.cwiseMax(-inner).cwiseMin(inner), n = (p - q).normalized();
          const Vec3f p_m = c + q + r * n;
          part.pos.insert(part.pos.end(), {p_m.x(), p_m.y(), p_m.z()});
          part.nor.insert(part.nor.end(), {n.x(), n.y(), n.z()});
          const float s_u = (c[u] + x) / repeat_m, s_v = (c[v] + y) / repeat_m;
          if (h[u] >= h[v])
            part.uv.insert(part.uv.end(), {s_u, s_v});
          else
            part.uv.insert(part.uv.end(), {s_v, s_u});
        }
      // e_u × e_v = e_a: (i, j), (i+1, j), (i+1, j+1) faces outward on the + side.
      const auto nu = std::uint32_t(su.size());
      for (std::uint32_t j = 0; j + 1 < sv.size(); ++j)
        for (std::uint32_t i = 0; i + 1 < nu; ++i) {
          const std::uint32_t p00 = base + j * nu + i, p10 = p00 + 1, p01 = p00 + nu, p11 = p01 + 1;
          if (sign > 0)
            part.idx.insert(part.idx.end(), {p00, p10, p11, p00, p11, p01});
          else
            part.idx.insert(part.idx.end(), {p00, p11, p10, p00, p01, p11});
        }
    }
}

// Walnut's growth rings across v, warped along u, in [0, 1) (periodic on the unit square).
float walnut_ring(float u, float v) {
  const float w = 12.0f * v + 0.18f * std::sin(2 * kPiF * 2 * u) + 0.06f * std::sin(2 * kPiF * (5 * u + 0.3f));
  return w - std::floor(w);
}

// Its colour: latewood dark, earlywood lighter, with fine pores along the grain.
Image walnut_colour(int size) {
  Image img(size, size, 3);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float u = (float(x) + 0.5f) / float(size), v = (float(y) + 0.5f) / float(size);
      const float ring = walnut_ring(u, v), late = ring * ring;
      const float pore = hash_to_unit(hash4(11, std::uint64_t(x / 8), std::uint64_t(y), 0)) < 0.06f ? 0.7f : 1.0f;
      const Rgb c = (Rgb(0.32f, 0.18f, 0.09f) * (1 - late) + Rgb(0.16f, 0.08f, 0.04f) * late) * pore;
      for (int k = 0; k < 3; ++k) img.at(x, y)[k] = linear_to_srgb(c[k]);
    }
  return img;
}

// Its relief, a tangent-space normal map (linear, (n + 1)/2): the height 0.4 mm × ring, so each
// ring ends in a small step, differenced over one texel of a 0.4 m repeat.
Image walnut_normals(int size) {
  const float texel_m = 0.4f / float(size), height_m = 0.0004f;
  auto h = [&](int x, int y) {
    x = (x + size) % size, y = (y + size) % size;
    return height_m * walnut_ring((float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size));
  };
  Image img(size, size, 3);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      // glTF's v runs down the image and the tangent frame's +y up it: ∂h/∂v = −∂h/∂y.
      const float dh_du = (h(x + 1, y) - h(x - 1, y)) / (2 * texel_m);
      const float dh_dv = -(h(x, y + 1) - h(x, y - 1)) / (2 * texel_m);
      const Vec3f n = Vec3f(-std::clamp(dh_du, -0.4f, 0.4f), -std::clamp(dh_dv, -0.4f, 0.4f), 1.0f).normalized();
      for (int k = 0; k < 3; ++k) img.at(x, y)[k] = 0.5f * (n[k] + 1);
    }
  return img;
}

std::vector<unsigned char> png_bytes(const Image& img, const fs::path& scratch) {
  write_image(scratch.string(), img);
  std::ifstream in(scratch, std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  fs::remove(scratch);
  if (bytes.empty()) throw std::runtime_error("cannot encode " + scratch.string());
  return bytes;
}

// The model under construction: one buffer, one bufferView per accessor or image.
struct GlbBuilder {
  tinygltf::Model model;
  GlbBuilder() {
    model.buffers.emplace_back();
    model.asset.version = "2.0";
    model.asset.generator = "insitu tools/demo_chair.cpp";
  }
  int view(const void* data, std::size_t bytes, int target) {
    auto& buf = model.buffers[0].data;
    tinygltf::BufferView bv;
    bv.buffer = 0;
    bv.byteOffset = buf.size();
    bv.byteLength = bytes;
    bv.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buf.insert(buf.end(), p, p + bytes);
    buf.resize((buf.size() + 3) / 4 * 4, 0);
    model.bufferViews.push_back(bv);
    return int(model.bufferViews.size() - 1);
  }
  int accessor(const std::vector<float>& v, int type, int width) {
    tinygltf::Accessor a;
    a.bufferView = view(v.data(), v.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.count = v.size() / std::size_t(width);
    a.type = type;
    if (type == TINYGLTF_TYPE_VEC3) {  // POSITION's bounds, which glTF requires
      a.minValues = {1e30, 1e30, 1e30}, a.maxValues = {-1e30, -1e30, -1e30};
      for (std::size_t i = 0; i < v.size(); ++i) {
        a.minValues[i % 3] = std::min(a.minValues[i % 3], double(v[i]));
        a.maxValues[i % 3] = std::max(a.maxValues[i % 3], double(v[i]));
      }
    }
    model.accessors.push_back(a);
    return int(model.accessors.size() - 1);
  }
  tinygltf::Primitive primitive(const Part& part, int material) {
    tinygltf::Primitive prim;
    prim.attributes["POSITION"] = accessor(part.pos, TINYGLTF_TYPE_VEC3, 3);
    prim.attributes["NORMAL"] = accessor(part.nor, TINYGLTF_TYPE_VEC3, 3);
    prim.attributes["TEXCOORD_0"] = accessor(part.uv, TINYGLTF_TYPE_VEC2, 2);
    tinygltf::Accessor a;
    a.bufferView = view(part.idx.data(), part.idx.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    a.count = part.idx.size();
    a.type = TINYGLTF_TYPE_SCALAR;
    model.accessors.push_back(a);
    prim.indices = int(model.accessors.size() - 1);
    prim.material = material;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    return prim;
  }
  int texture(const std::vector<unsigned char>& png, const std::string& name) {
    tinygltf::Image image;
    image.name = name;
    image.mimeType = "image/png";
    image.bufferView = view(png.data(), png.size(), 0);
    model.images.push_back(image);
    tinygltf::Texture tex;
    tex.source = int(model.images.size() - 1);
    tex.sampler = 0;
    model.textures.push_back(tex);
    return int(model.textures.size() - 1);
  }
};

using Obj = tinygltf::Value::Object;
tinygltf::Value num(double x) { return tinygltf::Value(x); }
tinygltf::Value rgb(double r, double g, double b) {
  return tinygltf::Value(tinygltf::Value::Array{num(r), num(g), num(b)});
}

tinygltf::Material pbr(const std::string& name, std::vector<double> base, double metallic, double roughness) {
  tinygltf::Material m;
  m.name = name;
  m.pbrMetallicRoughness.baseColorFactor = std::move(base);
  m.pbrMetallicRoughness.metallicFactor = metallic;
  m.pbrMetallicRoughness.roughnessFactor = roughness;
  return m;
}

// The four materials, in the order of the enum below.
enum { kWalnut, kVelvet, kSteel, kGlass };
void add_materials(GlbBuilder& b, const fs::path& scratch_dir) {
  const int colour = b.texture(png_bytes(walnut_colour(512), scratch_dir / "walnut_colour.png"), "walnut colour");
  const int relief = b.texture(png_bytes(walnut_normals(512), scratch_dir / "walnut_normals.png"), "walnut relief");
  tinygltf::Sampler repeat;
  repeat.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
  repeat.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
  b.model.samplers.push_back(repeat);

  tinygltf::Material walnut = pbr("lacquered walnut", {1, 1, 1, 1}, 0, 0.55);
  walnut.pbrMetallicRoughness.baseColorTexture.index = colour;
  walnut.normalTexture.index = relief;
  walnut.extensions["KHR_materials_clearcoat"] =
      tinygltf::Value(Obj{{"clearcoatFactor", num(1)}, {"clearcoatRoughnessFactor", num(0.04)}});
  tinygltf::Material velvet = pbr("rust velvet", {0.36, 0.09, 0.05, 1}, 0, 0.9);
  velvet.extensions["KHR_materials_sheen"] =
      tinygltf::Value(Obj{{"sheenColorFactor", rgb(0.75, 0.45, 0.35)}, {"sheenRoughnessFactor", num(0.4)}});
  tinygltf::Material steel = pbr("brushed steel", {0.6, 0.6, 0.62, 1}, 1, 0.3);
  tinygltf::Material glass = pbr("tinted glass", {1, 1, 1, 1}, 0, 0);
  glass.extensions["KHR_materials_transmission"] = tinygltf::Value(Obj{{"transmissionFactor", num(1)}});
  glass.extensions["KHR_materials_ior"] = tinygltf::Value(Obj{{"ior", num(1.5)}});
  glass.extensions["KHR_materials_volume"] = tinygltf::Value(Obj{
      {"thicknessFactor", num(0.02)}, {"attenuationDistance", num(0.05)}, {"attenuationColor", rgb(0.5, 0.8, 0.75)}});
  b.model.materials = {walnut, velvet, steel, glass};
  b.model.extensionsUsed = {"KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_transmission",
                            "KHR_materials_ior", "KHR_materials_volume"};
}

tinygltf::Mesh armchair(GlbBuilder& b) {
  Part frame, cushions, legs;
  const float wood_repeat_m = 0.4f;
  rounded_box(frame, {0, 0.345f, 0}, {0.36f, 0.025f, 0.33f}, 0.01f, wood_repeat_m);  // seat frame
  for (float sx : {-1.0f, 1.0f})
    rounded_box(frame, {sx * 0.335f, 0.5f, 0}, {0.025f, 0.13f, 0.33f}, 0.01f, wood_repeat_m);  // arms
  rounded_box(frame, {0, 0.6f, -0.305f}, {0.36f, 0.23f, 0.025f}, 0.01f, wood_repeat_m);        // back
  rounded_box(cushions, {0, 0.42f, 0.02f}, {0.30f, 0.05f, 0.30f}, 0.04f, 1);                   // seat
  rounded_box(cushions, {0, 0.63f, -0.225f}, {0.30f, 0.17f, 0.055f}, 0.045f, 1);               // back
  for (float sx : {-1.0f, 1.0f})
    for (float sz : {-1.0f, 1.0f})
      rounded_box(legs, {sx * 0.29f, 0.16f, sz * 0.27f}, {0.014f, 0.16f, 0.014f}, 0.013f, 1);
  tinygltf::Mesh mesh;
  mesh.name = "armchair";
  mesh.primitives = {b.primitive(frame, kWalnut), b.primitive(cushions, kVelvet), b.primitive(legs, kSteel)};
  return mesh;
}

tinygltf::Mesh side_table(GlbBuilder& b) {
  Part top, legs;
  rounded_box(top, {0, 0.52f, 0}, {0.24f, 0.01f, 0.24f}, 0.004f, 1);
  for (float sx : {-1.0f, 1.0f})
    for (float sz : {-1.0f, 1.0f})
      rounded_box(legs, {sx * 0.21f, 0.255f, sz * 0.21f}, {0.01f, 0.255f, 0.01f}, 0.009f, 1);
  tinygltf::Mesh mesh;
  mesh.name = "side table";
  mesh.primitives = {b.primitive(top, kGlass), b.primitive(legs, kSteel)};
  return mesh;
}

}  // namespace

void write_demo_chair(const std::string& glb_path) {
  GlbBuilder b;
  add_materials(b, fs::path(glb_path).parent_path());
  b.model.meshes = {armchair(b), side_table(b)};
  // A root node holding the chair and, 0.68 m to its right, the table.
  tinygltf::Node root, chair, table;
  root.name = "armchair set";
  root.children = {1, 2};
  chair.name = "armchair";
  chair.mesh = 0;
  table.name = "side table";
  table.mesh = 1;
  table.translation = {0.68, 0, 0.02};
  b.model.nodes = {root, chair, table};
  tinygltf::Scene scene;
  scene.nodes = {0};
  b.model.scenes = {scene};
  b.model.defaultScene = 0;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToFile(&b.model, glb_path, false, true, false, true))
    throw std::runtime_error("cannot write " + glb_path);
}

}  // namespace insitu
