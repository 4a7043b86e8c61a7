// glTF's normalTexture through the loader and the hit's shading normal (render/gltf_mesh.h,
// render/tangents.h, render/shading_normal.h): the texel's tilt in the MikkTSpace frame, or in the
// file's TANGENT frame where it has one, the scale as Blender's strength, and both sides.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/image.h"
#include "render/embree_scene.h"
#include "render/gltf_mesh.h"
#include "glb.h"
#include "test_util.h"

namespace insitu {
namespace {

using nlohmann::json;

// The normal map's one texel: tilted toward +u (red) and −v (green) by a few degrees.
const Rgb kTexel(165.0f / 255, 110.0f / 255, 235.0f / 255);

// A unit floor quad (normal +y) mapped u = x, v_gltf = 1 + z (so v up the image is −z), its
// material a normal map of the texel above with `scale` (or `material`, its texture 0 the texel);
// with `tangent`, a TANGENT attribute.
std::string write_mapped_quad(const test::TempDir& dir, double scale, const std::vector<float>& tangent = {},
                              const json& material = nullptr) {
  Image texel(1, 1, 3, 0.0f);
  texel.set_rgb(0, 0, kTexel);
  write_image(dir.file("n.png"), texel);
  std::string bin;
  test::append(bin, std::vector<float>{0, 0, 0, 1, 0, 0, 1, 0, -1, 0, 0, -1});  // POSITION
  test::append(bin, std::vector<float>{0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0});    // NORMAL
  test::append(bin, std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0});                // TEXCOORD_0
  test::append(bin, std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3});
  json attributes = {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}};
  json accessors = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                    {{"bufferView", 0}, {"byteOffset", 48}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                    {{"bufferView", 0}, {"byteOffset", 96}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                    {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}};
  json views = {{{"buffer", 0}, {"byteLength", 128}}, {{"buffer", 0}, {"byteOffset", 128}, {"byteLength", 12}}};
  if (!tangent.empty()) {
    const std::size_t at = bin.size();
    for (int i = 0; i < 4; ++i) test::append(bin, tangent);
    views.push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 64}});
    accessors.push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC4"}});
    attributes["TANGENT"] = 4;
  }
  const json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", attributes}, {"indices", 3}, {"material", 0}}}}}}},
      {"materials", {material.is_null() ? json{{"normalTexture", {{"index", 0}, {"scale", scale}}}} : material}},
      {"textures", {{{"source", 0}}}},
      {"images", {{{"uri", "n.png"}}}},
      {"accessors", accessors},
      {"bufferViews", views},
      {"buffers", {{{"uri", "q.bin"}, {"byteLength", bin.size()}}}}};
  std::ofstream(dir.file("q.bin"), std::ios::binary) << bin;
  return dir.write("q.gltf", doc.dump());
}

SurfacePoint surface_from(const std::string& path, float from_y, Warnings& w) {
  EmbreeScene scene({load_mesh(path, w)});
  const Ray ray{Vec3f(0.3f, from_y, -0.6f), Vec3f(0, from_y > 0 ? -1.0f : 1.0f, 0)};
  const Hit hit = scene.intersect(ray);
  EXPECT_TRUE(hit.valid());
  return scene.surface(ray, hit);
}

Vec3f shading_normal(const std::string& path, float from_y) {
  Warnings w;
  return surface_from(path, from_y, w).ns_world;
}

// The map's frame: t = ∂p/∂u = +x, n = +y, b = n × t = −z (= ∂p/∂v, v up the image); the normal is
// normalize((2c − 1) · (t, b, n)). Seen from below, the same normal, turned to the viewer.
TEST(GltfNormalMap, TheTexelTiltsTheNormalInTheMikkTSpaceFrame) {
  test::TempDir dir;
  const Rgb m = 2.0f * kTexel - 1.0f;
  const Vec3f expected = (m[0] * Vec3f(1, 0, 0) + m[1] * Vec3f(0, 0, -1) + m[2] * Vec3f(0, 1, 0)).normalized();
  const std::string path = write_mapped_quad(dir, 1.0);
  EXPECT_TRUE(shading_normal(path, 1).isApprox(expected, 1e-5f)) << shading_normal(path, 1).transpose();
  EXPECT_TRUE(shading_normal(path, -1).isApprox(-expected, 1e-5f));
  // A tilt of several degrees: the test tells a mapped normal from the plain one.
  EXPECT_LT(expected.y(), std::cos(5 * 3.14159265f / 180));
}

// normalTexture.scale is the Normal Map node's strength, as Blender imports it:
// normalize(n + s (N − n)).
TEST(GltfNormalMap, TheScaleIsBlendersStrength) {
  test::TempDir dir;
  const Vec3f n(0, 1, 0), full = shading_normal(write_mapped_quad(dir, 1.0), 1);
  for (const double s : {0.0, 0.5, 2.0}) {
    test::TempDir d;
    const Vec3f expected = (n + float(s) * (full - n)).normalized();
    EXPECT_TRUE(shading_normal(write_mapped_quad(d, s), 1).isApprox(expected, 1e-5f)) << "scale " << s;
  }
}

// The clear coat keeps the smooth normal however the normal map bends the rest
// (KHR_materials_clearcoat: "no normal mapping is applied to the clear coat layer"), and takes
// its own map's, clearcoatNormalTexture's, with its scale as the strength, where it has one;
// that map bends the coat alone. Both are rendered: no warning names them.
TEST(GltfNormalMap, TheClearCoatHasItsOwnNormal) {
  const Vec3f n(0, 1, 0);
  test::TempDir a, b;
  const Vec3f mapped = shading_normal(write_mapped_quad(a, 1.0), 1);
  Warnings w;
  const json base_mapped = {{"normalTexture", {{"index", 0}}},
                            {"extensions", {{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}}}}}};
  const SurfacePoint over_map = surface_from(write_mapped_quad(a, 1.0, {}, base_mapped), 1, w);
  EXPECT_TRUE(over_map.ns_world.isApprox(mapped, 1e-5f));
  EXPECT_TRUE(over_map.n_coat_world.isApprox(n, 1e-6f)) << over_map.n_coat_world.transpose();
  const json coat_mapped = {
      {"extensions",
       {{"KHR_materials_clearcoat",
         {{"clearcoatFactor", 1.0}, {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}}}}}}}};
  const SurfacePoint own = surface_from(write_mapped_quad(b, 1.0, {}, coat_mapped), -1, w);
  EXPECT_TRUE(own.ns_world.isApprox(-n, 1e-6f));
  EXPECT_TRUE(own.n_coat_world.isApprox(-(n + 0.5f * (mapped - n)).normalized(), 1e-5f))
      << own.n_coat_world.transpose();
  for (const std::string& item : w.items) EXPECT_EQ(item.find("not rendered"), std::string::npos) << item;
}

// A file's TANGENT is its frame: tangent −z with w = +1 gives b = n × t = (0, 1, 0) × (0, 0, −1) = −x.
TEST(GltfNormalMap, TheFilesTangentIsItsFrame) {
  test::TempDir dir;
  const Rgb m = 2.0f * kTexel - 1.0f;
  const Vec3f expected = (m[0] * Vec3f(0, 0, -1) + m[1] * Vec3f(-1, 0, 0) + m[2] * Vec3f(0, 1, 0)).normalized();
  EXPECT_TRUE(shading_normal(write_mapped_quad(dir, 1.0, {0, 0, -1, 1}), 1).isApprox(expected, 1e-5f));
}

// surface() reads three tangents a triangle: a mesh with any other count is refused when the scene
// is built, not read past its end.
TEST(GltfNormalMap, TangentsOtherThanThreeATriangleAreRefused) {
  test::TempDir dir;
  Warnings w;
  Mesh mesh = load_mesh(write_mapped_quad(dir, 1.0), w);
  ASSERT_EQ(mesh.tangents.size(), 3 * mesh.triangles.size());
  mesh.tangents.pop_back();
  EXPECT_THROW(EmbreeScene({mesh}), std::logic_error);
}

}  // namespace
}  // namespace insitu
