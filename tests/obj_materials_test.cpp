// MTL materials (render/obj_materials.h): the PBR extension's statements as Blender 3.4's OBJ
// importer sets its Principled BSDF (the expected values are its rules, computed by hand), the
// classic model kept, maps, normal maps, range errors by line, and what is named as not rendered.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>

#include "core/colour.h"
#include "core/image.h"
#include "core/sampler.h"
#include "interop/blender_meshes.h"
#include "obj_sphere.h"
#include "render/embree_scene.h"
#include "render/mesh.h"
#include "test_util.h"

namespace insitu {
namespace {

using test::TempDir;
using test::write_obj_sphere;

Mesh mtl_sphere(const TempDir& dir, const std::string& mtl, Warnings& w) {
  return load_obj(write_obj_sphere(dir, "ball", Vec3f::Zero(), 1.0f, mtl, 8), w);
}

const Material& mtl_first(const Mesh& m) { return m.materials[std::size_t(m.triangles[0].material)]; }

// A w × h image of one colour, 8-bit PNG (k/255 as stored).
void write_flat_mtl_png(const std::string& path, const Rgb& c, int w = 4, int h = 4) {
  Image img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.set_rgb(x, y, c);
  write_image(path, img);
}

bool mtl_warned(const Warnings& w, const std::string& text) {
  return std::any_of(w.items.begin(), w.items.end(), [&](const std::string& s) { return s.find(text) != s.npos; });
}

TEST(ObjMaterials, PbrStatementsMakeThePrincipledModel) {
  TempDir dir;
  Warnings w;
  const Mesh m =
      mtl_sphere(dir, "Kd 0.2 0.3 0.4\nKs 0.6 0.6 0.3\nPr 0.3\nPm 0.7\nPc 0.5\nPcr 0.2\nKe 0.1 0.2 0.3\n", w);
  const Material& mat = mtl_first(m);
  EXPECT_TRUE(mat.principled);
  EXPECT_TRUE(mat.kd.isApprox(Rgb(0.2f, 0.3f, 0.4f)));
  EXPECT_FLOAT_EQ(mat.roughness, 0.3f);
  EXPECT_FLOAT_EQ(mat.metallic, 0.7f);
  EXPECT_FLOAT_EQ(mat.specular, 0.5f);  // the mean of Ks, as Blender's importer
  EXPECT_FLOAT_EQ(mat.clearcoat, 0.5f);
  EXPECT_FLOAT_EQ(mat.clearcoat_roughness, 0.2f);
  EXPECT_TRUE(mat.emission.isApprox(Rgb(0.1f, 0.2f, 0.3f)));
  EXPECT_TRUE(w.items.empty()) << w.items.front();
}

TEST(ObjMaterials, AClassicMaterialStaysClassicAndEmits) {
  TempDir dir;
  Warnings w;
  const Material mat = mtl_first(mtl_sphere(dir, "Kd 0.5 0.5 0.5\nKs 0.04 0.04 0.04\nNs 100\nKe 2 1 0\n", w));
  EXPECT_FALSE(mat.principled);
  EXPECT_FLOAT_EQ(mat.ns, 100.0f);
  EXPECT_TRUE(mat.emission.isApprox(Rgb(2, 1, 0)));
}

// Without Pr, Blender's 1 − √(Ns/1000), or 1 without Ns; without Ks, Cycles's default 0.5; a map
// alone stands for its value (1 × the map).
TEST(ObjMaterials, WhatAPbrMaterialLeavesOutFollowsTheRules) {
  TempDir dir;
  write_flat_mtl_png(dir.file("grey.png"), Rgb::Constant(0.5f));
  Warnings w;
  const Material with_ns = mtl_first(mtl_sphere(dir, "Pm 0\nNs 250\n", w));
  EXPECT_FLOAT_EQ(with_ns.roughness, 1.0f - std::sqrt(0.25f));
  EXPECT_FLOAT_EQ(with_ns.specular, 0.5f);
  const Material huge_ns = mtl_first(mtl_sphere(dir, "Pm 0\nNs 5000\n", w));
  EXPECT_FLOAT_EQ(huge_ns.roughness, 0.0f);
  const Material bare = mtl_first(mtl_sphere(dir, "Pc 1\n", w));
  EXPECT_FLOAT_EQ(bare.roughness, 1.0f);
  EXPECT_FLOAT_EQ(bare.metallic, 0.0f);
  const Material maps = mtl_first(mtl_sphere(dir, "Ns 250\nmap_Pr grey.png\nmap_Pm grey.png\n", w));
  EXPECT_TRUE(maps.principled);
  EXPECT_FLOAT_EQ(maps.roughness, 1.0f);
  EXPECT_FLOAT_EQ(maps.metallic, 1.0f);
  ASSERT_TRUE(maps.map_roughness && maps.map_metallic);
  // Data, not colour: the stored 128/255, not its sRGB decoding (0.216).
  EXPECT_NEAR(maps.map_roughness.sample({Vec2f(0.3f, 0.6f), Vec2f::Zero()})[0], 128.0f / 255.0f, 1e-6f);
  EXPECT_FALSE(maps.map_roughness.srgb);
}

TEST(ObjMaterials, AMapMultipliesItsStatementsValue) {
  TempDir dir;
  write_flat_mtl_png(dir.file("grey.png"), Rgb::Constant(0.5f));
  write_flat_mtl_png(dir.file("glow.png"), Rgb(1.0f, 0.5f, 0.0f));
  Warnings w;
  const Material mat = mtl_first(mtl_sphere(dir, "Pr 0.8\nmap_Pr grey.png\nKe 2 2 2\nmap_Ke glow.png\n", w));
  EXPECT_FLOAT_EQ(mat.roughness, 0.8f);
  const UvSets uv{Vec2f(0.5f, 0.5f), Vec2f::Zero()};
  EXPECT_TRUE(mat.map_emission.srgb);  // a colour
  EXPECT_NEAR(mat.emitted(uv)[1], 2.0f * srgb_to_linear(128.0f / 255.0f), 1e-5f);
  const Material only_map = mtl_first(mtl_sphere(dir, "Pr 0.5\nmap_Ke glow.png\n", w));
  EXPECT_NEAR(only_map.emitted(uv)[0], 1.0f, 1e-6f);
}

TEST(ObjMaterials, NormGivesANormalMapWithTangents) {
  TempDir dir;
  write_flat_mtl_png(dir.file("n.png"), Rgb(0.6f, 0.5f, 1.0f));
  Warnings w;
  const Mesh m = mtl_sphere(dir, "Pr 0.4\nnorm -bm 0.7 n.png\n", w);
  const Material& mat = mtl_first(m);
  ASSERT_TRUE(mat.map_normal);
  EXPECT_FLOAT_EQ(mat.normal_strength, 0.7f);
  EXPECT_FALSE(mat.map_normal.srgb);
  EXPECT_EQ(m.tangents.size(), 3 * m.triangles.size());
  // The sphere's UVs run along +u eastward: every tangent is a unit vector with a sign.
  for (const Vec4f& t : m.tangents) {
    EXPECT_NEAR(t.head<3>().norm(), 1.0f, 1e-4f);
    EXPECT_EQ(std::abs(t.w()), 1.0f);
  }
}

// map_Bump holds a normal map where Blender's exporter writes one; a grey height map is named.
TEST(ObjMaterials, MapBumpIsANormalMapOnlyWhereItsImageIsOne) {
  TempDir dir;
  write_flat_mtl_png(dir.file("n.png"), Rgb(0.5f, 0.5f, 1.0f));
  write_flat_mtl_png(dir.file("height.png"), Rgb::Constant(0.7f));
  Warnings w;
  const Mesh normal = mtl_sphere(dir, "Kd 0.5 0.5 0.5\nmap_Bump -bm 0.5 n.png\n", w);
  EXPECT_TRUE(mtl_first(normal).map_normal);
  EXPECT_FALSE(mtl_first(normal).principled);
  EXPECT_FLOAT_EQ(mtl_first(normal).normal_strength, 0.5f);
  EXPECT_FALSE(normal.tangents.empty());
  EXPECT_TRUE(w.items.empty());
  const Mesh height = mtl_sphere(dir, "Kd 0.5 0.5 0.5\nbump height.png\n", w);
  EXPECT_FALSE(mtl_first(height).map_normal);
  EXPECT_TRUE(height.tangents.empty());
  EXPECT_TRUE(mtl_warned(w, "map_Bump is a height map"));
}

TEST(ObjMaterials, SheenAndAnisotropyAreNamedAsNotRendered) {
  TempDir dir;
  Warnings w;
  mtl_sphere(dir, "Pr 0.5\nPs 0.3\naniso 0.5\nanisor 0.25\n", w);
  EXPECT_TRUE(mtl_warned(w, "not rendered: Ps, aniso, anisor"));
}

TEST(ObjMaterials, OutOfRangeValuesNameTheLine) {
  TempDir dir;
  for (const auto& [statement, message] :
       std::vector<std::pair<std::string, std::string>>{{"Pr 1.5", "Pr 1.5 is outside [0, 1]"},
                                                        {"Pm -0.1", "Pm -0.1 is outside [0, 1]"},
                                                        {"Pc nan", "not a finite number"},
                                                        {"anisor x", "'x' is not a number"},
                                                        {"Ke -1 0 0", "Ke -1 is negative"},
                                                        {"Tf 1 1.5 1", "Tf 1.5 is outside [0, 1] (a transmittance)"}}) {
    Warnings w;
    try {
      mtl_sphere(dir, "Kd 0.5 0.5 0.5\n" + statement + "\n", w);
      ADD_FAILURE() << statement << " was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), dir.file("ball.mtl") + ":3") << statement;  // after "newmtl m", Kd
      EXPECT_NE(e.message().find(message), std::string::npos) << e.what();
    }
  }
  Warnings w;
  write_flat_mtl_png(dir.file("n.png"), Rgb(0.5f, 0.5f, 1.0f));
  EXPECT_THROW(mtl_sphere(dir, "norm missing.png\n", w), InputError);
}

TEST(ObjMaterials, DependenciesListEveryMap) {
  TempDir dir;
  for (const char* f : {"r.png", "m.png", "n.png", "e.png"}) write_flat_mtl_png(dir.file(f), Rgb(0.5f, 0.5f, 1.0f));
  const std::string obj =
      write_obj_sphere(dir, "ball", Vec3f::Zero(), 1, "map_Pr r.png\nmap_Pm m.png\nnorm n.png\nmap_Ke e.png\n", 4);
  std::vector<std::string> names;
  for (const std::string& f : obj_dependencies(obj)) names.push_back(std::filesystem::path(f).filename().string());
  for (const char* f : {"ball.mtl", "r.png", "m.png", "n.png", "e.png"})
    EXPECT_NE(std::find(names.begin(), names.end(), f), names.end()) << f;
}

// `d` and `map_d` as Blender 3.4's importer links them to the Principled BSDF's Alpha: a
// stochastic opacity of d × map_d's alpha channel, or × its grey (as data) where it has none, in
// either model; `Tr` ignored, as Blender does. A quad of opacity a is met by a fraction a of the
// rays straight through it (binomial, 4σ).
TEST(ObjMaterials, DAndMapDAreAStochasticOpacity) {
  TempDir dir;
  Image rgba(4, 4, 4, 1.0f);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) rgba.at(x, y)[3] = 64.0f / 255;
  write_image(dir.file("cut.png"), rgba);
  write_flat_mtl_png(dir.file("grey.png"), Rgb::Constant(128.0f / 255));
  const UvSets uv{Vec2f(0.3f, 0.6f), Vec2f::Zero()};
  Warnings w;
  const Material d = mtl_first(mtl_sphere(dir, "Kd 1 1 1\nd 0.25\n", w));
  EXPECT_FALSE(d.principled);
  EXPECT_EQ(d.alpha_mode, Material::AlphaMode::kBlend);
  EXPECT_FLOAT_EQ(d.opacity(uv), 0.25f);
  EXPECT_FALSE(mtl_warned(w, "fully transparent"));
  mtl_sphere(dir, "d 0\n", w);
  EXPECT_TRUE(mtl_warned(w, "material 'm': d 0: the surface is fully transparent"));
  for (const char* opaque : {"d 1\n", "Tr 0.75\n", "Kd 1 1 1\n"})
    EXPECT_FALSE(mtl_first(mtl_sphere(dir, opaque, w)).cutout()) << opaque;
  const Material alpha = mtl_first(mtl_sphere(dir, "Pr 0.5\nd 0.5\nmap_d cut.png\n", w));
  EXPECT_TRUE(alpha.principled);
  EXPECT_NEAR(alpha.opacity(uv), 0.5f * 64 / 255, 1e-6f);
  const Material grey = mtl_first(mtl_sphere(dir, "map_d grey.png\n", w));
  EXPECT_NEAR(grey.opacity(uv), 128.0f / 255, 1e-6f);  // as stored: data, not sRGB-decoded
  std::vector<std::string> names;
  for (const std::string& f : obj_dependencies(dir.file("ball.obj")))
    names.push_back(std::filesystem::path(f).filename().string());
  EXPECT_NE(std::find(names.begin(), names.end(), "grey.png"), names.end());
  EXPECT_THROW(mtl_sphere(dir, "map_d missing.png\n", w), InputError);
  std::string bytes;  // the export's opacity (blender_prelude.py's opaque_by)
  const std::string line =
      blender_mesh(mtl_sphere(dir, "Pr 0.5\nd 0.5\nmap_d cut.png\n", w), "ball", std::nullopt, bytes);
  EXPECT_NE(line.find("\"opacity\": 0.5, \"opacity_texture\": \""), std::string::npos) << line;
  EXPECT_NE(line.find("cut.png\", \"opacity_channel\": \"Alpha\""), std::string::npos) << line;

  // Rays straight down through a unit quad at z = 0 (the OBJ's own, not a sphere: one crossing).
  const int n = 20000;
  for (float a : {0.0f, 0.3f, 0.75f}) {
    std::ofstream(dir.file("quad.mtl")) << fmt::format("newmtl m\nKd 1 1 1\nd {}\n", a);
    std::ofstream(dir.file("quad.obj")) << "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl m\nf 1 2 3 4\n";
    std::vector<Mesh> meshes;
    meshes.push_back(load_obj(dir.file("quad.obj"), w));
    const EmbreeScene scene(std::move(meshes));
    double hit = 0;
    for (int k = 0; k < n; ++k) {
      Sampler s(3, std::uint64_t(k), 0);
      const Ray ray{Vec3f(0.05f + 0.9f * s.next(), 0.05f + 0.9f * s.next(), 1.0f), Vec3f(0, 0, -1)};
      hit += scene.intersect(ray, 0.0f, 2.0f).valid();
    }
    EXPECT_NEAR(hit / n, a, 4 * std::sqrt(a * (1 - a) / n) + 1e-9) << a;
  }
}

// The export carries the principled values and maps to blender_prelude.py's principled_material.
// Tf (or Kt) and Ni, as Blender 3.4's exporter writes a Principled BSDF's Transmission and IOR with
// the PBR extension and its importer reads them back: the mean of Tf, and Ni (1.45, a new
// Principled BSDF's, without it). The classic model has no transmission: its Tf, the filter of
// what `d` lets through, stays ignored.
TEST(ObjMaterials, TfAndNiAreThePrincipledGlass) {
  TempDir dir;
  Warnings w;
  const Material glass = mtl_first(mtl_sphere(dir, "Kd 1 1 1\nPr 0\nTf 1 1 1\nNi 1.5\n", w));
  EXPECT_FLOAT_EQ(glass.transmission, 1.0f);
  EXPECT_FLOAT_EQ(glass.ior, 1.5f);
  const Material tinted = mtl_first(mtl_sphere(dir, "Pr 0.3\nTf 0.2 0.5 0.8\n", w));
  EXPECT_FLOAT_EQ(tinted.transmission, 0.5f);
  EXPECT_FLOAT_EQ(tinted.ior, 1.45f);
  EXPECT_FLOAT_EQ(mtl_first(mtl_sphere(dir, "Pr 0.3\nKt 0.25 0.25 0.25\nNi 1.33\n", w)).transmission, 0.25f);
  const Material classic = mtl_first(mtl_sphere(dir, "Kd 0.5 0.5 0.5\nTf 1 1 1\nNi 1.5\n", w));
  EXPECT_FALSE(classic.principled);
  EXPECT_FLOAT_EQ(classic.transmission, 0.0f);
  EXPECT_TRUE(w.items.empty()) << w.items.front();
  // Carried into Blender as the Principled BSDF's inputs.
  std::string bytes;
  const std::string line = blender_mesh(mtl_sphere(dir, "Pr 0\nTf 1 1 1\nNi 1.5\n", w), "ball", std::nullopt, bytes);
  EXPECT_NE(line.find("\"transmission\": 1, \"ior\": 1.5"), std::string::npos) << line;
  // An index that refracts nothing sensible where light passes is refused; where none passes, it
  // is not read (old exporters write Ni 0 into every material).
  try {
    mtl_sphere(dir, "Pr 0\nTf 1 1 1\nNi 0\n", w);
    ADD_FAILURE() << "Ni 0 was accepted for a glass";
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("Ni 0 with Tf"), std::string::npos) << e.what();
  }
  EXPECT_FLOAT_EQ(mtl_first(mtl_sphere(dir, "Pr 0\nTf 0 0 0\nNi 0\n", w)).transmission, 0.0f);
  EXPECT_FALSE(mtl_first(mtl_sphere(dir, "Kd 0.5 0.5 0.5\nNi 0\n", w)).principled);
}

// "Kd r" is a grey, as the MTL specification says, whatever the colour statement; the last
// statement of a material counts.
TEST(ObjMaterials, AColourOfOneNumberIsAGrey) {
  TempDir dir;
  Warnings w;
  const Material m = mtl_first(mtl_sphere(dir, "Kd 0.5\nKs 0.04\nKe 2\nPr 0.5\nTf 0.3\n", w));
  EXPECT_TRUE(m.kd.isApprox(Rgb::Constant(0.5f))) << m.kd.transpose();
  EXPECT_TRUE(m.ks.isApprox(Rgb::Constant(0.04f))) << m.ks.transpose();
  EXPECT_TRUE(m.emission.isApprox(Rgb::Constant(2.0f))) << m.emission.transpose();
  EXPECT_FLOAT_EQ(m.transmission, 0.3f);
  const Material again = mtl_first(mtl_sphere(dir, "Kd 0.5\nKd 0.1 0.2 0.3\n", w));
  EXPECT_TRUE(again.kd.isApprox(Rgb(0.1f, 0.2f, 0.3f))) << again.kd.transpose();
}

// A texture statement's -s and -o, as Blender 3.4's importer reads them (a Mapping node of that
// Scale and Location): (u, v) → s·(u, v) + o, then the OBJ convention's image point (u′, 1 − v′).
// A 4 × 4 map of value (i + 4j)/15 at texel column i, row j (j = 0 at the top) is sampled where the
// placement lands on texel centres, which bilinear filtering returns exactly.
TEST(ObjMaterials, TextureOptionsPlaceTheMapAsBlendersMappingNode) {
  TempDir dir;
  Image img(4, 4, 3);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) img.set_rgb(i, j, Rgb::Constant(float(i + 4 * j) / 15.0f));
  write_image(dir.file("ramp.png"), img);
  Warnings w;
  const Material m = mtl_first(mtl_sphere(dir, "Pr 1\nmap_Pr -s 2 3 1 -o 0.5 0.25 0 ramp.png\n", w));
  // Texel (3, 1): its centre (0.875, 0.375) is u′ = 0.875, v′ = 0.625 = 2u + 0.5, 3v + 0.25.
  const auto stored = [](int i, int j) { return std::round(float(i + 4 * j) / 15.0f * 255.0f) / 255.0f; };
  EXPECT_NEAR(m.map_roughness.sample({Vec2f(0.1875f, 0.125f), Vec2f::Zero()})[0], stored(3, 1), 1e-6f);
  // Texel (0, 3) at (0.125, 0.875): u′ = 1.125 and v′ = 1.125, 1 − v′ = −0.125 (the map repeats).
  EXPECT_NEAR(m.map_roughness.sample({Vec2f(0.3125f, 0.2916667f), Vec2f::Zero()})[0], stored(0, 3), 1e-5f);
  // Without the options the same point is the OBJ convention's (0.1875, 0.875): between texels.
  const Material plain = mtl_first(mtl_sphere(dir, "Pr 1\nmap_Pr ramp.png\n", w));
  EXPECT_GT(std::abs(plain.map_roughness.sample({Vec2f(0.1875f, 0.125f), Vec2f::Zero()})[0] - stored(3, 1)), 0.1f);
  // Carried into Blender as that Mapping node; a map without options as its path alone.
  std::string bytes;
  const std::string line =
      blender_mesh(mtl_sphere(dir, "Pr 1\nmap_Pr -s 2 3 1 -o 0.5 0.25 0 ramp.png\n", w), "ball", std::nullopt, bytes);
  EXPECT_NE(line.find("\"scale\": (2, 3), \"offset\": (0.5, 0.25)}"), std::string::npos) << line;
  EXPECT_EQ(blender_mesh(mtl_sphere(dir, "Pr 1\nmap_Pr ramp.png\n", w), "ball", std::nullopt, bytes).find("scale"),
            std::string::npos);
}

TEST(ObjMaterials, TheExportNamesThePrincipledMaterial) {
  TempDir dir;
  write_flat_mtl_png(dir.file("grey.png"), Rgb::Constant(0.5f));
  Warnings w;
  const Mesh m = mtl_sphere(dir, "Kd 0.2 0.3 0.4\nPr 0.25\nmap_Pr grey.png\nPm 0.5\nPc 1\nKe 0 0 0\n", w);
  std::string bytes;
  const std::string line = blender_mesh(m, "ball", std::nullopt, bytes);
  EXPECT_NE(line.find("principled_material(\"ball: m\""), std::string::npos) << line;
  EXPECT_NE(line.find("\"roughness\": 0.25"), std::string::npos) << line;
  EXPECT_NE(line.find("\"metallic\": 0.5"), std::string::npos) << line;
  EXPECT_NE(line.find("\"clearcoat\": 1"), std::string::npos) << line;
  EXPECT_NE(line.find("grey.png"), std::string::npos) << line;
}

}  // namespace
}  // namespace insitu
