// glTF 2.0 input (render/gltf_mesh.h, render/gltf_materials.h): the node hierarchy, .gltf with a
// .bin and .glb alike, data URIs, materials and textures with KHR_texture_transform, glTF's default
// material, the refusals; and a principled object in the white furnace.
#include <gtest/gtest.h>

#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>

#include "integrators/registry.h"
#include "core/colour.h"
#include "cube_fixture.h"
#include "render/embree_scene.h"
#include "render/gltf_mesh.h"
#include "scene/pipeline.h"
#include "scene/scene_file.h"
#include "scene_fixture.h"
#include "gltf_fixture.h"
#include "test_util.h"

namespace insitu {
namespace {

using nlohmann::json;
using test::append;
using test::base64;

// One triangle with normals and UVs (glTF's convention, v down), under a parent node translated
// by (1, 2, 3) whose child turns it 90° about +y and scales it by 2. `material` and `extra`
// (merged into the document) make the variants.
struct GltfTriangle {
  std::string bin;
  json doc;
  GltfTriangle() {
    append(bin, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});  // POSITION
    append(bin, std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1});  // NORMAL
    append(bin, std::vector<float>{0, 0, 1, 0, 0, 1});           // TEXCOORD_0
    append(bin, std::vector<std::uint16_t>{0, 1, 2, 0});         // indices (padded to 4 bytes)
    const float s = std::sqrt(0.5f);
    doc = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes",
         {{{"translation", {1, 2, 3}}, {"children", {1}}},
          {{"rotation", {0, s, 0, s}}, {"scale", {2, 2, 2}}, {"mesh", 0}}}},
        {"meshes",
         {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}}}}}}},
        {"accessors",
         {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
          {{"bufferView", 0}, {"byteOffset", 36}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
          {{"bufferView", 0}, {"byteOffset", 72}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}},
          {{"bufferView", 1}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}},
        {"bufferViews", {{{"buffer", 0}, {"byteLength", 96}}, {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 8}}}},
        {"buffers", {{{"byteLength", bin.size()}}}}};
  }
  std::string write_gltf(const test::TempDir& dir, const std::string& name) {
    doc["buffers"][0]["uri"] = name + ".bin";
    std::ofstream(dir.file(name + ".bin"), std::ios::binary) << bin;
    return dir.write(name + ".gltf", doc.dump());
  }
  std::string write_data_uri(const test::TempDir& dir, const std::string& name) {
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(bin);
    return dir.write(name + ".gltf", doc.dump());
  }
  std::string write_glb(const test::TempDir& dir, const std::string& name) {
    json d = doc;
    d["buffers"][0].erase("uri");
    std::ofstream(dir.file(name + ".glb"), std::ios::binary) << test::glb(d, bin);
    return dir.file(name + ".glb");
  }
};

void expect_placed(const Mesh& m) {
  ASSERT_EQ(m.triangles.size(), 1u);
  ASSERT_EQ(m.positions.size(), 3u);
  // p_world = T (R_y(90°) (2 p)): (1, 0, 0) ↦ (0, 0, −2) ↦ (1, 2, 1); (0, 1, 0) ↦ (1, 4, 3).
  EXPECT_TRUE(m.positions[0].isApprox(Vec3f(1, 2, 3), 1e-6f));
  EXPECT_TRUE(m.positions[1].isApprox(Vec3f(1, 2, 1), 1e-6f));
  EXPECT_TRUE(m.positions[2].isApprox(Vec3f(1, 4, 3), 1e-6f));
  EXPECT_TRUE(m.normals[0].isApprox(Vec3f(1, 0, 0), 1e-6f));  // +z turned about +y
  // UVs in OBJ's convention: v = 1 − v_gltf.
  EXPECT_TRUE(m.uvs[1].isApprox(Vec2f(1, 1)));
  EXPECT_TRUE(m.uvs[2].isApprox(Vec2f(0, 0)));
  ASSERT_EQ(m.materials.size(), 1u);  // glTF's default material alone
  EXPECT_TRUE(m.materials[0].principled);
  EXPECT_EQ(m.materials[0].metallic, 1.0f);
  EXPECT_EQ(m.materials[0].roughness, 1.0f);
}

TEST(Gltf, NodesPlaceTheirMeshesInEveryContainer) {
  test::TempDir dir;
  GltfTriangle g;
  Warnings w;
  const std::string gltf = g.write_gltf(dir, "a");
  expect_placed(load_mesh(gltf, w));
  EXPECT_EQ(mesh_dependencies(gltf), std::vector<std::string>{dir.file("a.bin")});
  expect_placed(load_mesh(g.write_glb(dir, "b"), w));
  expect_placed(load_mesh(g.write_data_uri(dir, "c"), w));
  EXPECT_TRUE(mesh_dependencies(dir.file("c.gltf")).empty());
  EXPECT_TRUE(w.items.empty()) << w.items.front();
}

// A 2 × 1 PNG, stored values k/255: left texel (255, 0, 0), right (0, 128, 255).
std::string two_texel_png(const test::TempDir& dir) {
  Image img(2, 1, 3, 0.0f);
  img.set_rgb(0, 0, Rgb(1, 0, 0));
  img.set_rgb(1, 0, Rgb(0, 128.0f / 255, 1));
  const std::string path = dir.file("t.png");
  write_image(path, img);
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(Gltf, MaterialsReadTheirFactorsAndTextures) {
  test::TempDir dir;
  GltfTriangle g;
  g.doc["images"] = {{{"uri", "data:image/png;base64," + base64(two_texel_png(dir))}}};
  g.doc["textures"] = {{{"source", 0}}};
  // The base colour through KHR_texture_transform offset (0.5, 0): u = 0.25 reads the right texel.
  g.doc["materials"] = {
      {{"name", "lacquer"},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {0.5, 0.25, 1, 1}},
         {"metallicFactor", 0.5},
         {"roughnessFactor", 0.8},
         {"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0}}}}}}}},
         {"metallicRoughnessTexture", {{"index", 0}}}}}}};
  g.doc["meshes"][0]["primitives"][0]["material"] = 0;
  Warnings w;
  const Mesh m = load_mesh(g.write_gltf(dir, "m"), w);
  ASSERT_EQ(m.materials.size(), 1u);  // glTF's default material only where a primitive uses it
  const Material& mat = m.materials[0];
  EXPECT_EQ(mat.name, "lacquer");
  EXPECT_TRUE(mat.principled);
  EXPECT_EQ(mat.metallic, 0.5f);
  EXPECT_EQ(mat.roughness, 0.8f);
  // Texel centres at s = 0.25 and 0.75. Base colour: sRGB-decoded, times the factor.
  const UvSets at_left = {Vec2f(0.25f, 0.5f), Vec2f::Zero()};
  const Rgb base = mat.base_colour(at_left);
  EXPECT_NEAR(base[0], 0.0f, 1e-6f);
  EXPECT_NEAR(base[1], 0.25f * srgb_to_linear(128.0f / 255), 1e-5f);
  EXPECT_NEAR(base[2], 1.0f, 1e-6f);
  // Metallic-roughness: linear, untransformed, left texel: G = 0, B = 0.
  EXPECT_TRUE(mat.map_metallic_roughness.sample(at_left).isApprox(Rgb(1, 0, 0)));
  const UvSets at_right = {Vec2f(0.75f, 0.5f), Vec2f::Zero()};
  EXPECT_NEAR(mat.map_metallic_roughness.sample(at_right)[1], 128.0f / 255, 1e-6f);
}

// An embedded JPEG is known by its bytes: a data URI that does not say image/jpeg decodes as JPEG.
TEST(Gltf, AnEmbeddedJpegIsKnownByItsBytes) {
  test::TempDir dir;
  write_image(dir.file("grey.jpg"), Image(8, 8, 3, 0.5f));
  std::ifstream in(dir.file("grey.jpg"), std::ios::binary);
  const std::string jpeg{std::istreambuf_iterator<char>(in), {}};
  GltfTriangle g;
  g.doc["images"] = {{{"uri", "data:application/octet-stream;base64," + base64(jpeg)}}};
  g.doc["textures"] = {{{"source", 0}}};
  g.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  g.doc["meshes"][0]["primitives"][0]["material"] = 0;
  Warnings w;
  const Mesh m = load_mesh(g.write_gltf(dir, "j"), w);
  ASSERT_TRUE(m.materials[0].map_kd);
  EXPECT_TRUE(m.materials[0].map_kd.srgb);
  // 0.5 stored as 128/255 (JPEG's rounding of a flat grey is exact to a level), decoded after.
  EXPECT_NEAR(m.materials[0].base_colour({Vec2f(0.5f, 0.5f), Vec2f::Zero()})[1], srgb_to_linear(128.0f / 255), 0.01f);
}

TEST(Gltf, RefusalsNameTheJsonPath) {
  test::TempDir dir;
  Warnings w;
  auto error_of = [&](GltfTriangle g) {
    try {
      load_mesh(g.write_gltf(dir, "bad"), w);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  GltfTriangle cycle;
  cycle.doc["nodes"][1]["children"] = {0};
  EXPECT_NE(error_of(cycle).find("bad.gltf: $.nodes[0]: the node hierarchy is not a tree"), std::string::npos)
      << error_of(cycle);
  GltfTriangle strip;
  strip.doc["meshes"][0]["primitives"][0]["mode"] = 5;
  EXPECT_NE(error_of(strip).find("bad.gltf: the default scene holds no triangles"), std::string::npos);
  GltfTriangle nan;
  std::memcpy(nan.bin.data() + 4, "\x00\x00\xc0\x7f", 4);  // a NaN in POSITION
  EXPECT_NE(error_of(nan).find("bad.gltf: $.accessors[0] (POSITION): a value is not finite"), std::string::npos);
  GltfTriangle texcoord;
  texcoord.doc["accessors"][2]["type"] = "VEC3";
  EXPECT_NE(error_of(texcoord).find("$.accessors[2] (TEXCOORD_0): expected 2 components"), std::string::npos);
}

// A GLB whose BIN chunk declares 8 bytes more than follow its header, the buffer as long as the
// declared chunk: tinygltf 2.7 alone copies 8 bytes from past the end of the file (fuzz_gltf).
TEST(Gltf, AGlbBinChunkLongerThanTheFileIsRefused) {
  test::TempDir dir;
  Warnings w;
  GltfTriangle g;
  g.doc["buffers"][0]["byteLength"] = g.bin.size() + 8;
  std::string bytes = test::glb(g.doc, g.bin);
  const std::size_t bin_at = bytes.size() - g.bin.size() - 8;
  const auto declared = std::uint32_t(g.bin.size() + 8);
  std::memcpy(bytes.data() + bin_at, &declared, 4);
  std::ofstream(dir.file("long.glb"), std::ios::binary) << bytes;
  try {
    load_mesh(dir.file("long.glb"), w);
    ADD_FAILURE() << "a BIN chunk running past the end of the file was read";
  } catch (const InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find(fmt::format("long.glb: byte {}: the BIN chunk declares {} bytes, but {} follow",
                                               bin_at, g.bin.size() + 8, g.bin.size())),
        std::string::npos)
        << e.what();
  }
  expect_placed(load_mesh(GltfTriangle().write_glb(dir, "whole"), w));  // the chunk whole
}

// glTF 2.0 §3.6.2.3: a sparse accessor's values replace its elements at its indices; without a
// buffer view the other elements are zeros. POSITION's vertex 2, (0, 1, 0), becomes (0, 3, 0),
// placed by the nodes at (1, 2 + 2·3, 3); a TEXCOORD_0 of zeros gets (1, 0) at vertex 1, which is
// OBJ's (1, 1).
GltfTriangle sparse_triangle(std::uint16_t index) {
  GltfTriangle g;
  append(g.bin, std::vector<std::uint16_t>{index, 0});  // at 104: the sparse index (padded)
  append(g.bin, std::vector<float>{0, 3, 0});           // at 108: POSITION's value
  append(g.bin, std::vector<float>{1, 0});              // at 120: TEXCOORD_0's value
  g.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 104}, {"byteLength", 4}});
  g.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 108}, {"byteLength", 12}});
  g.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 120}, {"byteLength", 8}});
  g.doc["buffers"][0]["byteLength"] = g.bin.size();
  g.doc["accessors"][0]["sparse"] = {
      {"count", 1}, {"indices", {{"bufferView", 2}, {"componentType", 5123}}}, {"values", {{"bufferView", 3}}}};
  g.doc["accessors"][2].erase("bufferView");
  g.doc["accessors"][2].erase("byteOffset");
  g.doc["accessors"][2]["sparse"] = {
      {"count", 1}, {"indices", {{"bufferView", 2}, {"componentType", 5123}}}, {"values", {{"bufferView", 4}}}};
  return g;
}

TEST(Gltf, SparseAccessorsReplaceTheirElements) {
  test::TempDir dir;
  Warnings w;
  const Mesh m = load_mesh(sparse_triangle(2).write_glb(dir, "sparse"), w);
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_TRUE(m.positions[0].isApprox(Vec3f(1, 2, 3), 1e-6f));
  EXPECT_TRUE(m.positions[2].isApprox(Vec3f(1, 8, 3), 1e-6f)) << m.positions[2].transpose();
  ASSERT_EQ(m.uvs.size(), 3u);
  EXPECT_TRUE(m.uvs[0].isApprox(Vec2f(0, 1)));  // zeros: glTF's (0, 0)
  EXPECT_TRUE(m.uvs[1].isApprox(Vec2f(0, 1)));  // index 2 only: vertex 1 keeps zeros
  EXPECT_TRUE(m.uvs[2].isApprox(Vec2f(1, 1))) << m.uvs[2].transpose();
  try {
    load_mesh(sparse_triangle(5).write_glb(dir, "bad"), w);
    ADD_FAILURE() << "a sparse index out of range was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.glb: $.accessors[0].sparse.indices: index 5 at 0 is out of range"),
              std::string::npos)
        << e.what();
  }
  GltfTriangle huge = sparse_triangle(2);  // nothing but this bounds a view-less accessor's memory
  huge.doc["accessors"][2]["count"] = 1 << 25;
  try {
    load_mesh(huge.write_glb(dir, "huge"), w);
    ADD_FAILURE() << "a view-less accessor of 2^25 elements was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("$.accessors[2] (TEXCOORD_0): 33554432 elements without a buffer view"),
              std::string::npos)
        << e.what();
  }
}

// A closed box of smooth white metal (glTF's principled material) in a constant environment
// reflects the environment: L = 0.7 within the standard error, the single-scattering loss at
// α = 0.0025 being far below it.
TEST(Gltf, SmoothWhiteMetalPassesTheWhiteFurnace) {
  test::TempDir dir;
  GltfTriangle g;
  g.bin.clear();
  append(g.bin, std::vector<float>{-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1});
  append(g.bin, std::vector<std::uint16_t>{0, 3, 2, 0, 2, 1, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                           3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5});
  g.doc["nodes"] = {{{"mesh", 0}}};
  g.doc["meshes"][0]["primitives"][0] = {{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 0}};
  g.doc["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 8}, {"type", "VEC3"}},
                        {{"bufferView", 1}, {"componentType", 5123}, {"count", 36}, {"type", "SCALAR"}}};
  g.doc["bufferViews"] = {{{"buffer", 0}, {"byteLength", 96}}, {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 72}}};
  g.doc["buffers"][0]["byteLength"] = g.bin.size();
  g.doc["materials"] = {{{"pbrMetallicRoughness", {{"metallicFactor", 1.0}, {"roughnessFactor", 0.05}}}}};
  Warnings w;
  std::vector<Mesh> meshes;
  meshes.push_back(load_mesh(g.write_gltf(dir, "box"), w));
  const EmbreeScene box(std::move(meshes));
  const CubeMap env = test::constant_cube(8, Rgb(0.7f, 0.7f, 0.7f));
  RenderInputs in;
  in.objects = &box;
  in.environment = &env;
  const auto path = make_integrator("path", in);
  const Ray ray{Vec3f(0.3f, 0.5f, 5), Vec3f(-0.05f, -0.1f, -1).normalized()};
  double sum = 0, sum2 = 0;
  const int n = 2000;
  for (int k = 0; k < n; ++k) {
    Sampler s(5, 0, std::uint64_t(k));
    const double x = path->sample(ray, s).radiance[1];
    sum += x, sum2 += x * x;
  }
  const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
  EXPECT_NEAR(mean, 0.7, 4 * se + 1e-3);
}

// A scene file names a glTF object as an OBJ one; the integrators that shade by the base colour
// alone say which materials they flatten, and `path` says nothing.
TEST(Gltf, TheSceneFileLoadsItAndOtherIntegratorsSayWhatTheyFlatten) {
  test::SceneFixture fx;
  const json metal = {{"name", "brushed steel"},
                      {"pbrMetallicRoughness", {{"metallicFactor", 1.0}, {"roughnessFactor", 0.3}}}};
  test::write_gltf_sphere(fx.dir, "ball", Vec3f(0.5f, 0.2f, -0.5f), 0.2f, metal, 8);
  fx.scene["objects"] = {{{"mesh", "ball.gltf"}, {"translate", {0.0, 0.1, 0.0}}}};
  auto warnings_with = [&](const std::string& integrator) {
    fx.scene["render"]["integrator"] = integrator;
    const LoadedScene s = load_scene(parse_scene_file(fx.write()));
    EXPECT_NEAR(mesh_bounds(s.objects->meshes()[0]).lo.y(), 0.1f, 1e-5f);
    std::string all;
    for (const std::string& w : s.warnings.items) all += w + "\n";
    return all;
  };
  EXPECT_EQ(warnings_with("path").find("base colour only"), std::string::npos);
  for (const char* integrator : {"realtime", "irradiance"}) {
    const std::string all = warnings_with(integrator);
    EXPECT_NE(all.find("shades the objects by their base colour only; metallic, roughness, specular, clear coat, "
                       "sheen, glass and emission are the path integrator's (materials 'brushed steel')"),
              std::string::npos)
        << integrator << ": " << all;
  }
}

}  // namespace
}  // namespace insitu
