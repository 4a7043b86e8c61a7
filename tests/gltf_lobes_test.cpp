// glTF's material extensions and modes beyond metal/roughness (render/gltf_materials.h):
// KHR_materials_clearcoat, KHR_materials_sheen, KHR_materials_specular, emission with
// KHR_materials_emissive_strength, and alphaMode MASK and BLEND as cut-outs (render/embree_scene.h),
// read from the file and rendered.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <OpenImageIO/imageio.h>

#include "core/sampler.h"
#include "cube_fixture.h"
#include "gltf_fixture.h"
#include "integrators/registry.h"
#include "render/bsdf.h"
#include "render/embree_scene.h"
#include "render/gltf_mesh.h"
#include "test_util.h"

namespace insitu {
namespace {

using nlohmann::json;

// A unit quad in the plane z = 0, (0, 0)–(1, 1), facing +z, with UVs u = x, v = y (glTF's v down:
// v_gltf = 1 − y) and one material.
std::string write_quad(const test::TempDir& dir, const std::string& name, const json& material,
                       const json& extra = json::object()) {
  std::string bin;
  test::append(bin, std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
  test::append(bin, std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0});
  test::append(bin, std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3});
  json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}, {"material", 0}}}}}}},
      {"materials", {material}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 0}, {"byteOffset", 48}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", 80}}, {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 12}}}},
      {"buffers", {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}}}};
  doc.merge_patch(extra);
  std::ofstream(dir.file(name + ".bin"), std::ios::binary) << bin;
  return dir.write(name + ".gltf", doc.dump());
}

// A 2 × 1 RGBA PNG: both texels grey 128, alpha 51 (0.2) on the left, 204 (0.8) on the right;
// written straight (unassociated), as glTF's images are.
std::string write_alpha_png(const test::TempDir& dir) {
  const unsigned char pixels[8] = {128, 128, 128, 51, 128, 128, 128, 204};
  OIIO::ImageSpec spec(2, 1, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);
  auto out = OIIO::ImageOutput::create(dir.file("alpha.png"));
  EXPECT_TRUE(out && out->open(dir.file("alpha.png"), spec) && out->write_image(OIIO::TypeDesc::UINT8, pixels));
  out->close();
  return "alpha.png";
}

TEST(GltfLobes, ExtensionsAndModesAreRead) {
  test::TempDir dir;
  const json material = {
      {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0.6}}, {"baseColorTexture", {{"index", 0}}}}},
      {"alphaMode", "MASK"},
      {"alphaCutoff", 0.4},
      {"emissiveFactor", {1, 0.5, 0.25}},
      {"normalTexture", {{"index", 0}}},
      {"extensions",
       {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}},
        {"KHR_materials_iridescence", {{"iridescenceFactor", 0.5}}},
        {"KHR_materials_clearcoat",
         {{"clearcoatFactor", 0.7}, {"clearcoatRoughnessFactor", 0.2}, {"clearcoatTexture", {{"index", 0}}}}},
        {"KHR_materials_sheen",
         {{"sheenColorFactor", {0.5, 0.4, 0.3}},
          {"sheenRoughnessFactor", 0.6},
          {"sheenRoughnessTexture", {{"index", 0}}}}}}}};
  const json images = {{"images", {{{"uri", write_alpha_png(dir)}}}}, {"textures", {{{"source", 0}}}}};
  Warnings w;
  const Mesh m = load_mesh(write_quad(dir, "q", material, images), w);
  const Material& mat = m.materials[0];
  EXPECT_EQ(mat.alpha_mode, Material::AlphaMode::kMask);
  EXPECT_FLOAT_EQ(mat.alpha_cutoff, 0.4f);
  EXPECT_FLOAT_EQ(mat.alpha, 0.6f);
  EXPECT_TRUE(mat.emission.isApprox(Rgb(4, 2, 1)));
  EXPECT_FLOAT_EQ(mat.clearcoat, 0.7f);
  EXPECT_FLOAT_EQ(mat.clearcoat_roughness, 0.2f);
  EXPECT_TRUE(bool(mat.map_clearcoat));
  EXPECT_TRUE(mat.sheen.isApprox(Rgb(0.5f, 0.4f, 0.3f)));
  EXPECT_FLOAT_EQ(mat.sheen_roughness, 0.6f);
  // Opacity 0.6 × 0.2 = 0.12 at the left texel, 0.6 × 0.8 = 0.48 at the right: the cutoff 0.4
  // keeps the right one only. The colour is the PNG's as stored, not premultiplied by its alpha.
  const UvSets left = {Vec2f(0.25f, 0.5f), Vec2f::Zero()}, right = {Vec2f(0.75f, 0.5f), Vec2f::Zero()};
  EXPECT_NEAR(mat.map_kd.sample_alpha(left), 0.2f, 1e-6f);
  EXPECT_EQ(mat.opacity(left), 0.0f);
  EXPECT_EQ(mat.opacity(right), 1.0f);
  EXPECT_NEAR(mat.map_kd.sample(left)[0], mat.map_kd.sample(right)[0], 1e-6f);
  // The sheen's roughness is its texture's alpha (as Blender's importer connects it).
  EXPECT_NEAR(mat.map_sheen_roughness.sample_alpha(left), 0.2f, 1e-6f);
  EXPECT_TRUE(bool(mat.map_normal));
  EXPECT_FLOAT_EQ(mat.normal_strength, 1.0f);  // glTF's default scale
  // What is read goes unremarked; the extension insitu lacks is named.
  ASSERT_EQ(w.items.size(), 1u);
  EXPECT_NE(w.items[0].find("not rendered yet: KHR_materials_iridescence"), std::string::npos) << w.items[0];
  EXPECT_EQ(w.items[0].find("normalTexture"), std::string::npos) << w.items[0];
  EXPECT_EQ(w.items[0].find("clearcoat"), std::string::npos) << w.items[0];
  EXPECT_EQ(w.items[0].find("sheen"), std::string::npos) << w.items[0];
}

// KHR_materials_specular as Blender 3.4's importer reads it: Specular = (lum(c) − t)/(1 − t) ·
// F0(ior)/0.08 with lum = 0.3 R + 0.6 G + 0.1 B, × specularFactor. For c = (1, 0.7, 0.45),
// lum = 0.765: 0.765 · 0.04/0.08 = 0.3825 at ior 1.5; at ior 2, F0 = 1/9: 1.0625; with t = 0.5,
// (0.765 − 0.5)/0.5 = 0.53 → 0.265; × specularFactor 0.5 → 0.19125.
TEST(GltfLobes, SpecularIsReadAsBlenderReadsIt) {
  test::TempDir dir;
  auto read = [&](const json& more) {
    json ext = {{"specularColorFactor", {1, 0.7, 0.45}}};
    if (more.is_object()) ext.merge_patch(more);  // ({} is null: a merge would replace ext)
    json material = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.2, 0.08, 1}}}},
                     {"extensions", {{"KHR_materials_specular", ext}}}};
    if (more.contains("ior")) material["extensions"]["KHR_materials_ior"] = {{"ior", more["ior"]}};
    if (more.contains("t")) material["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", more["t"]}};
    Warnings w;
    const Material m = load_mesh(write_quad(dir, "s", material), w).materials[0];
    EXPECT_TRUE(w.items.empty());
    return m;
  };
  EXPECT_NEAR(read({}).specular, 0.3825f, 1e-6f);
  EXPECT_NEAR(read({{"ior", 2.0}}).specular, 1.0625f, 1e-5f);
  EXPECT_NEAR(read({{"t", 0.5}}).specular, 0.265f, 1e-6f);
  EXPECT_NEAR(read({{"specularFactor", 0.5}}).specular, 0.19125f, 1e-6f);
  // The tint against this base colour (lum 0.278): ĉ_s − 1 = (0.30719, −0.08497, −0.41176),
  // ĉ_b − 1 = (0.79856, −0.28058, −0.71223), their ratios (0.38468, 0.30283, 0.57813), whose
  // lum is 0.35492.
  const Material m = read({});
  EXPECT_NEAR(m.specular_tint(Rgb(0.5f, 0.2f, 0.08f)), 0.35492f, 1e-4f);
  EXPECT_EQ(m.specular_tint(Rgb(0.3f, 0.3f, 0.3f)), 1.0f);  // a grey base: Blender's 1
  Material plain;
  EXPECT_EQ(plain.specular_tint(Rgb(0.5f, 0.2f, 0.08f)), 0.0f);  // no extension, no tint
  Material white = m;
  white.specular_colour = Rgb::Ones();
  EXPECT_EQ(white.specular_tint(Rgb(0.5f, 0.2f, 0.08f)), 0.0f);  // a white colour asks for none
}

// The extension's textures scale its factors (Material::specular_at): the colour by
// specularColorTexture's sRGB-decoded RGB, the strength by specularTexture's alpha. alpha.png's
// texels are grey 128/255 (linear ((128/255 + 0.055)/1.055)^2.4) of alpha 0.2 and 0.8, so at
// their centres Specular = 0.5 · a · lum(c · g) · F0(1.5)/0.08, F0(1.5)/0.08 = 0.5, and the
// tint is the factor's alone (a grey texture changes no hue). The BSDF uses the same values.
TEST(GltfLobes, SpecularTexturesScaleTheirFactors) {
  test::TempDir dir;
  const json images = {{"images", {{{"uri", write_alpha_png(dir)}}}}, {"textures", {{{"source", 0}}}}};
  const json ext = {{"specularFactor", 0.5},
                    {"specularColorFactor", {1, 0.7, 0.45}},
                    {"specularTexture", {{"index", 0}}},
                    {"specularColorTexture", {{"index", 0}}}};
  const json material = {{"pbrMetallicRoughness",
                          {{"baseColorFactor", {0.5, 0.2, 0.08, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 0.4}}},
                         {"extensions", {{"KHR_materials_specular", ext}}}};
  Warnings w;
  const Material m = load_mesh(write_quad(dir, "t", material, images), w).materials[0];
  EXPECT_TRUE(w.items.empty()) << w.items[0];
  const float grey = std::pow((128.0f / 255.0f + 0.055f) / 1.055f, 2.4f), lum = 0.765f * grey;
  const UvSets left = {Vec2f(0.25f, 0.5f), Vec2f::Zero()}, right = {Vec2f(0.75f, 0.5f), Vec2f::Zero()};
  EXPECT_NEAR(m.specular_at(left, 0.0f), 0.5f * 0.2f * lum * 0.5f, 1e-6f);
  EXPECT_NEAR(m.specular_at(right, 0.0f), 0.5f * 0.8f * lum * 0.5f, 1e-6f);
  EXPECT_NEAR(m.specular_tint(m.kd, m.specular_colour_at(left)), 0.35492f, 1e-4f);
  // The BSDF at the right texel is the principled one of those parameters.
  PrincipledParams p{m.kd, m.metallic, m.roughness, 0.5f * 0.8f * lum * 0.5f};
  p.specular_tint = 0.35492f;
  const Vec3f wo = Vec3f(0.3f, 0.1f, 1).normalized(), wi = Vec3f(-0.4f, 0.2f, 1).normalized();
  const Rgb expected = Bsdf::principled(p).eval(wo, wi), got = Bsdf::from_material(m, right).eval(wo, wi);
  EXPECT_LT((got - expected).abs().maxCoeff(), 1e-4f * expected.maxCoeff()) << got.transpose();
}

TEST(GltfLobes, BadSpecularFactorsAreNamed) {
  test::TempDir dir;
  Warnings w;
  try {
    load_mesh(
        write_quad(dir, "b", {{"extensions", {{"KHR_materials_specular", {{"specularColorFactor", {1, -1, 1}}}}}}}), w);
    ADD_FAILURE() << "a negative specular colour was read";
  } catch (const InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find("b.gltf: $.materials[0].extensions.KHR_materials_specular.specularColorFactor"),
        std::string::npos)
        << e.what();
  }
}

// Cycles's tint (svm/closure.h): F0 = 0.08 s (1 − st + st · base/lum(base)). At normal incidence
// with ωi = ωo only F changes with the tint, by 0.08 s · st · (base/lum − 1) · (1 − F_h), so the
// difference of two evaluations is proportional, channel by channel, to base/lum − 1: for base
// (0.8, 0.4, 0.2), lum 0.5, that is (0.6, −0.2, −0.6). A grey base has no hue: no change.
TEST(GltfLobes, SpecularTintTurnsTheDielectricTowardTheBaseHue) {
  const Vec3f n(0, 0, 1);
  auto f = [&](const Rgb& base, float tint) {
    PrincipledParams p{base, 0.0f, 0.3f, 0.5f};
    p.specular_tint = tint;
    return Bsdf::principled(p).eval(n, n);
  };
  const Rgb base(0.8f, 0.4f, 0.2f), d = f(base, 1) - f(base, 0);
  EXPECT_GT(d[0], 0.0f);
  EXPECT_NEAR(d[0] / d[2], -1.0f, 1e-4f);
  EXPECT_NEAR(d[1] / d[2], 1.0f / 3.0f, 1e-4f);
  const Rgb grey(0.4f, 0.4f, 0.4f), dg = f(grey, 1) - f(grey, 0);
  EXPECT_LT(dg.abs().maxCoeff(), 1e-6f * f(grey, 0).maxCoeff());
}

// A texture with alpha filters its colour associated: halfway between a white texel that is there
// and a black one that is not, the colour is white (Σ w a c / Σ w a), and the alpha a half; where
// no texel is there, the plain mean.
TEST(GltfLobes, ColourIsFilteredByAlpha) {
  Texture t;
  auto image = std::make_shared<Texels>(Image(2, 1, 3, 0.0f));
  image->floats.set_rgb(0, 0, Rgb(1, 0.5f, 0.25f));
  auto alpha = std::make_shared<Texels>(Image(2, 1, 1, 0.0f));
  *alpha->floats.at(0, 0) = 1.0f;
  t.image = image, t.alpha = alpha;
  t.image_from_uv = Texture::obj_convention();
  const UvSets midway = {Vec2f(0.5f, 0.5f), Vec2f::Zero()};
  EXPECT_TRUE(t.sample(midway).isApprox(Rgb(1, 0.5f, 0.25f), 1e-6f)) << t.sample(midway).transpose();
  EXPECT_NEAR(t.sample_alpha(midway), 0.5f, 1e-6f);
  *alpha->floats.at(0, 0) = 0.0f;
  EXPECT_TRUE(t.sample(midway).isApprox(Rgb(0.5f, 0.25f, 0.125f), 1e-6f)) << t.sample(midway).transpose();
}

// A texture held as an 8-bit file's bytes samples as the same texels held as floats k/255 (the
// obviously correct form): colour, sRGB-encoded colour, and colour filtered by an alpha channel.
TEST(GltfLobes, ByteTexelsSampleAsTheirFloats) {
  const int w = 5, h = 3;
  ByteImage rgb{w, h, 3, {}}, a{w, h, 1, {}};
  for (int i = 0; i < w * h * 3; ++i) rgb.data.push_back(std::uint8_t((i * 97 + 13) % 256));
  for (int i = 0; i < w * h; ++i) a.data.push_back(std::uint8_t((i * 53 + 200) % 256));
  auto floats_of = [](const ByteImage& b) {
    Image f(b.width, b.height, b.channels);
    for (std::size_t i = 0; i < b.data.size(); ++i) f.data[i] = float(b.data[i]) / 255.0f;
    return std::make_shared<const Texels>(std::move(f));
  };
  for (bool srgb : {false, true})
    for (bool with_alpha : {false, true}) {
      Texture bytes, floats;
      bytes.image = std::make_shared<const Texels>(rgb), floats.image = floats_of(rgb);
      if (with_alpha) bytes.alpha = std::make_shared<const Texels>(a), floats.alpha = floats_of(a);
      bytes.srgb = floats.srgb = srgb;
      for (int k = 0; k < 50; ++k) {
        const UvSets uv = {Vec2f(0.137f * float(k) - 2.0f, 0.071f * float(k * k % 17)), Vec2f::Zero()};
        ASSERT_TRUE(bytes.sample(uv).isApprox(floats.sample(uv), 1e-6f)) << k;
        ASSERT_NEAR(bytes.sample_alpha(uv), floats.sample_alpha(uv), 1e-6f) << k;
      }
    }
}

TEST(GltfLobes, BadValuesAreRefusedWithTheirPath) {
  test::TempDir dir;
  auto error_of = [&](const json& material) {
    Warnings w;
    try {
      load_mesh(write_quad(dir, "bad", material), w);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of({{"alphaMode", "CLIP"}}).find("bad.gltf: $.materials[0].alphaMode: 'CLIP' is not OPAQUE"),
            std::string::npos);
  EXPECT_NE(error_of({{"extensions", {{"KHR_materials_clearcoat", {{"clearcoatFactor", 2}}}}}})
                .find("$.materials[0].extensions.KHR_materials_clearcoat: clearcoatFactor"),
            std::string::npos);
  EXPECT_NE(error_of({{"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", -1}}}}}})
                .find("KHR_materials_emissive_strength.emissiveStrength: must be ≥ 0"),
            std::string::npos);
}

// Rays straight down through the quad (z = 1 → −1) at n points spread over it: the fraction that
// intersect() reports hit, and the transmittance() of each.
struct Fractions {
  double hit = 0;
  std::vector<float> transmittance;
};
Fractions hit_fractions(const EmbreeScene& scene, int n) {
  Fractions f;
  for (int k = 0; k < n; ++k) {
    Sampler s(3, std::uint64_t(k), 0);
    const Ray ray{Vec3f(0.05f + 0.9f * s.next(), 0.05f + 0.9f * s.next(), 1.0f), Vec3f(0, 0, -1)};
    f.hit += scene.intersect(ray, 0.0f, 2.0f).valid();
    f.transmittance.push_back(scene.transmittance(ray, 0.0f, 2.0f));
  }
  f.hit /= n;
  return f;
}

// BLEND is stochastic opacity for traced rays: a quad of alpha a is met by a fraction a of them
// (binomial, 4σ). A shadow ray is attenuated by 1 − a, every one of them, with no noise (Cycles's
// transparent shadows). MASK is all or nothing for both.
TEST(GltfLobes, CutOutsLetRaysThroughByTheirOpacity) {
  test::TempDir dir;
  const int n = 20000;
  for (double a : {0.0, 0.3, 0.75}) {
    Warnings w;
    std::vector<Mesh> meshes;
    meshes.push_back(
        load_mesh(write_quad(dir, "blend",
                             {{"alphaMode", "BLEND"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, a}}}}}),
                  w));
    const EmbreeScene scene(std::move(meshes));
    const Fractions f = hit_fractions(scene, n);
    EXPECT_NEAR(f.hit, a, 4 * std::sqrt(a * (1 - a) / n) + 1e-9) << a;
    for (float t : f.transmittance) ASSERT_FLOAT_EQ(t, float(1 - a)) << a;
  }
  for (double a : {0.3, 0.75}) {
    Warnings w;
    std::vector<Mesh> meshes;
    meshes.push_back(load_mesh(
        write_quad(dir, "mask", {{"alphaMode", "MASK"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, a}}}}}),
        w));
    const EmbreeScene scene(std::move(meshes));
    const Fractions f = hit_fractions(scene, 2000);
    EXPECT_EQ(f.hit, a >= 0.5 ? 1.0 : 0.0) << a;
    for (float t : f.transmittance) ASSERT_EQ(t, a >= 0.5 ? 0.0f : 1.0f) << a;
  }
}

// Two sheets of alpha 0.3 over the unit square, each a fan of 256 long thin triangles from its
// centre, over an opaque floor: a shadow ray through both sheets keeps 0.7², through one 0.7, and
// one that reaches the floor 0; one that misses everything keeps exactly 1. (Embree may report a
// triangle twice along a ray in a spatial-split BVH, which the filter guards against; this
// scene, with up to 8192 triangles a sheet, did not make it do so.)
TEST(GltfLobes, ShadowRaysThroughSheerSheetsKeepTheirTransmittance) {
  Mesh sheets;
  Material sheer;
  sheer.alpha_mode = Material::AlphaMode::kBlend;
  sheer.alpha = 0.3f;
  sheets.materials = {sheer, Material{}};
  const int per_side = 64;
  for (float z : {0.0f, 0.5f}) {
    const auto centre = std::uint32_t(sheets.positions.size());
    sheets.positions.push_back(Vec3f(0.5f, 0.5f, z));
    for (int k = 0; k < 4 * per_side; ++k) {  // the square's boundary, counter-clockwise
      const float t = float(k % per_side) / per_side;
      const Vec2f corner[5] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
      const Vec2f p = corner[k / per_side] + t * (corner[k / per_side + 1] - corner[k / per_side]);
      sheets.positions.push_back(Vec3f(p.x(), p.y(), z));
    }
    for (int k = 0; k < 4 * per_side; ++k)
      sheets.triangles.push_back(
          {{centre, centre + 1 + std::uint32_t(k), centre + 1 + std::uint32_t((k + 1) % (4 * per_side))},
           {-1, -1, -1},
           {-1, -1, -1},
           0});
  }
  const auto f = std::uint32_t(sheets.positions.size());  // the floor, z = −1, over x < 0.5
  sheets.positions.insert(sheets.positions.end(),
                          {Vec3f(-1, -1, -1), Vec3f(0.5f, -1, -1), Vec3f(0.5f, 2, -1), Vec3f(-1, 2, -1)});
  sheets.triangles.push_back({{f, f + 1, f + 2}, {-1, -1, -1}, {-1, -1, -1}, 1});
  sheets.triangles.push_back({{f, f + 2, f + 3}, {-1, -1, -1}, {-1, -1, -1}, 1});
  std::vector<Mesh> meshes;
  meshes.push_back(std::move(sheets));
  const EmbreeScene scene(std::move(meshes));
  for (int k = 0; k < 4000; ++k) {
    Sampler s(5, std::uint64_t(k), 0);
    const Vec3f o(0.02f + 0.96f * s.next(), 0.02f + 0.96f * s.next(), 1.0f);
    const Ray down{o, Vec3f(0, 0, -1)};
    EXPECT_FLOAT_EQ(scene.transmittance(down, 0.0f, 1.75f), 0.49f) << o.transpose();  // both sheets
    EXPECT_FLOAT_EQ(scene.transmittance(down, 0.0f, 0.75f), 0.7f) << o.transpose();   // the upper one
    if (o.x() < 0.5f)
      EXPECT_EQ(scene.transmittance(down, 0.0f, 3.0f), 0.0f) << o.transpose();  // the floor stops it
    else
      EXPECT_FLOAT_EQ(scene.transmittance(down, 0.0f, 3.0f), 0.49f) << o.transpose();
    EXPECT_EQ(scene.transmittance({o, Vec3f(0, 0, 1)}, 0.0f, 10.0f), 1.0f);  // away from everything
  }
}

// The path integrator over `scene` in a black world.
std::unique_ptr<Integrator> path_in_the_dark(const EmbreeScene& scene) {
  static const CubeMap black = test::constant_cube(8, Rgb::Zero());
  RenderInputs in;
  in.objects = &scene;
  in.environment = &black;
  return make_integrator("path", in);
}

// An emitting object of black base colour in a black room is seen at its emitted radiance:
// emissiveFactor × emissiveStrength, in the environment's units (Cycles's strength 1 = radiance 1),
// with no variance.
TEST(GltfLobes, EmissionIsSeenAtItsRadiance) {
  test::TempDir dir;
  const json material = {{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 0}}},
                         {"emissiveFactor", {1, 0.5, 0.25}},
                         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 3}}}}}};
  Warnings w;
  std::vector<Mesh> meshes;
  meshes.push_back(load_mesh(write_quad(dir, "lamp", material), w));
  const EmbreeScene scene(std::move(meshes));
  const auto path = path_in_the_dark(scene);
  for (int k = 0; k < 16; ++k) {
    Sampler s(9, 0, std::uint64_t(k));
    const Rgb L = path->sample({Vec3f(0.5f, 0.4f, 2.0f), Vec3f(0, 0, -1)}, s).radiance;
    EXPECT_TRUE(L.isApprox(Rgb(3, 1.5f, 0.75f), 1e-6f)) << L.transpose();
  }
}

// The path integrator's camera ray crosses sheer surfaces instead of choosing between them. An
// emitting BLEND quad of alpha 0.4 and radiance 1 in a black world covers 0.4 of every sample, at
// radiance 1 (its reflection sees only black): no noise at all, where choosing per sample gave
// coverage 0 or 1. Behind it a second, of alpha 0.5, brings the coverage to 0.4 + 0.6 · 0.5 = 0.7
// in every sample (their radiance then holds their reflections of each other too).
TEST(GltfLobes, CameraRaysCrossSheerSurfacesWithoutChoosing) {
  test::TempDir dir;
  const auto sheer = [&](const std::string& name, double alpha, float z) {
    const json material = {{"alphaMode", "BLEND"},
                           {"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, alpha}}, {"metallicFactor", 0}}},
                           {"emissiveFactor", {1, 1, 1}}};
    Warnings w;
    Mesh m = load_mesh(write_quad(dir, name, material), w);
    for (Vec3f& p : m.positions) p.z() = z;
    return m;
  };
  for (int quads : {1, 2}) {
    std::vector<Mesh> meshes;
    meshes.push_back(sheer("front", 0.4, 0.5f));
    if (quads == 2) meshes.push_back(sheer("back", 0.5, 0.0f));
    const EmbreeScene scene(std::move(meshes));
    const auto path = path_in_the_dark(scene);
    for (int k = 0; k < 64; ++k) {
      Sampler s(9, 0, std::uint64_t(k));
      const CameraSample cs = path->sample({Vec3f(0.5f, 0.4f, 2.0f), Vec3f(0, 0, -1)}, s);
      EXPECT_NEAR(cs.coverage, quads == 1 ? 0.4f : 0.7f, 1e-6f) << quads;
      if (quads == 1) {
        EXPECT_TRUE(cs.radiance.isApprox(Rgb(1, 1, 1), 1e-6f)) << cs.radiance.transpose();
      }
    }
  }
}

// Past 16 sheer surfaces the camera ray chooses: twenty quads of alpha 0.1 cover 1 − 0.9¹⁶ of
// every sample for certain, and the last four take the rest, 0.9¹⁶, whole or not at all: with
// probability 1 − 0.9⁴ the sample's coverage is 1, else 1 − 0.9¹⁶ (binomial, 4σ).
// Twenty sheer quads of alpha 0.1 over the unit square, at z = 0, −0.1, … −1.9.
std::vector<Mesh> twenty_sheer_quads(const test::TempDir& dir) {
  std::vector<Mesh> meshes;
  for (int k = 0; k < 20; ++k) {
    Warnings w;
    Mesh m = load_mesh(
        write_quad(dir, "q" + std::to_string(k),
                   {{"alphaMode", "BLEND"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 0.1}}}}}),
        w);
    for (Vec3f& p : m.positions) p.z() = -0.1f * float(k);
    meshes.push_back(std::move(m));
  }
  return meshes;
}

// More sheer surfaces than the shadow filter keeps in place: each still attenuates, once.
TEST(GltfLobes, ShadowRaysThroughTwentySheerSurfacesKeepTheirTransmittance) {
  test::TempDir dir;
  const EmbreeScene scene(twenty_sheer_quads(dir));
  for (int k = 0; k < 1000; ++k) {
    Sampler s(6, std::uint64_t(k), 0);
    const Ray down{Vec3f(0.1f + 0.8f * s.next(), 0.1f + 0.8f * s.next(), 1.0f), Vec3f(0, 0, -1)};
    EXPECT_NEAR(scene.transmittance(down, 0.0f, 3.0f), std::pow(0.9, 20), 1e-5) << down.origin.transpose();
    EXPECT_NEAR(scene.transmittance(down, 0.0f, 1.55f), std::pow(0.9, 6), 1e-5) << down.origin.transpose();
  }
}

TEST(GltfLobes, PastSixteenSheerSurfacesTheCameraRayChooses) {
  test::TempDir dir;
  const EmbreeScene scene(twenty_sheer_quads(dir));
  const auto path = path_in_the_dark(scene);
  const double certain = 1 - std::pow(0.9, 16), whole = 1 - std::pow(0.9, 4);
  const int n = 4000;
  int full = 0;
  for (int k = 0; k < n; ++k) {
    Sampler s(4, 0, std::uint64_t(k));
    const Ray ray{Vec3f(0.1f + 0.8f * s.next(), 0.1f + 0.8f * s.next(), 1.0f), Vec3f(0, 0, -1)};
    const float c = path->sample(ray, s).coverage;
    ASSERT_TRUE(std::abs(c - 1) < 1e-5 || std::abs(c - certain) < 1e-5) << c;
    full += std::abs(c - 1) < 1e-5;
  }
  EXPECT_NEAR(double(full) / n, whole, 4 * std::sqrt(whole * (1 - whole) / n));
}

}  // namespace
}  // namespace insitu
