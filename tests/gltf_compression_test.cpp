// Compressed glTF (render/gltf_decompress.h): a sphere written plain, with EXT_meshopt_compression
// and KHR_mesh_quantization, and with KHR_draco_mesh_compression (gltf_compressed_fixture.h, each
// encoded by the library's own encoder) loads as the same mesh within the quantization's error;
// broken streams are refused with their JSON path; export-blender carries a decompressed copy.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "gltf_compressed_fixture.h"
#include "render/gltf_mesh.h"
#include "scene_fixture.h"
#include "test_util.h"
#include "uv_sphere.h"

namespace insitu {
namespace {

using nlohmann::json;
using test::make_uv_sphere;
using test::UvSphere;

constexpr float kRadius = 0.5f;
const float kCentre[3] = {0.1f, 0.6f, -0.2f};

UvSphere sphere() { return make_uv_sphere(8, 16, kCentre, kRadius); }

// The three files of the test sphere in `dir`.
std::string write_plain(const test::TempDir& dir) { return dir.write("plain.glb", test::plain_sphere_glb(sphere())); }
std::string write_meshopt(const test::TempDir& dir) {
  return dir.write("meshopt.glb", test::meshopt_sphere_glb(sphere()));
}
std::string write_draco(const test::TempDir& dir) { return dir.write("draco.glb", test::draco_sphere_glb(sphere())); }

// The quantization's worst error on each attribute (half a step of its grid).
struct Tolerance {
  float position, normal, uv;
};

// Each triangle of `b` is a triangle of `a` (the one whose centroid is nearest; the same winding,
// its corners possibly rotated) within `tol`; both have as many.
void expect_same_triangles(const Mesh& a, const Mesh& b, const Tolerance& tol) {
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  auto centroid = [](const Mesh& m, const Triangle& t) {
    return (m.positions[t.v[0]] + m.positions[t.v[1]] + m.positions[t.v[2]]) / 3;
  };
  for (const Triangle& tb : b.triangles) {
    const Vec3f cb = centroid(b, tb);
    const Triangle* best = nullptr;
    for (const Triangle& ta : a.triangles)
      if (!best || (centroid(a, ta) - cb).norm() < (centroid(a, *best) - cb).norm()) best = &ta;
    int rotation = -1;
    for (int r = 0; r < 3; ++r)
      if ((a.positions[best->v[r]] - b.positions[tb.v[0]]).norm() < 2 * tol.position) rotation = r;
    ASSERT_GE(rotation, 0) << "no corner matches";
    for (int k = 0; k < 3; ++k) {
      const int ka = (k + rotation) % 3;
      EXPECT_LT((a.positions[best->v[ka]] - b.positions[tb.v[k]]).cwiseAbs().maxCoeff(), tol.position);
      EXPECT_LT((a.normals[best->n[ka]] - b.normals[tb.n[k]]).cwiseAbs().maxCoeff(), tol.normal);
      EXPECT_LT((a.uvs[best->t[ka]] - b.uvs[tb.t[k]]).cwiseAbs().maxCoeff(), tol.uv);
    }
  }
}

// An octahedral map's coordinates (s, t) off by at most δ each move v = (s, t, 1 − |s| − |t|) by
// at most √6 δ, and n = v / |v| (|v| ≥ 1/√3) by at most √3 · √6 δ < 4.25 δ.
constexpr float kOctahedralGain = 4.25f;

// Positions in tenths of a millimetre: 0.05 mm; normals by meshopt's octahedral map at 8 bits, its
// coordinates in steps of 1/127: δ = 1/254; UVs: half of 1/65535.
TEST(GltfCompression, MeshoptLoadsAsThePlainFile) {
  test::TempDir dir;
  Warnings w;
  const Mesh plain = load_mesh(write_plain(dir), w);
  const Mesh packed = load_mesh(write_meshopt(dir), w);
  EXPECT_EQ(packed.positions.size(), plain.positions.size());
  expect_same_triangles(plain, packed, {0.05e-3f + 1e-6f, kOctahedralGain / 254, 0.5f / 65535 + 1e-6f});
}

// Draco's grid: positions over the box's largest side (2r) in 2¹⁴ − 1 steps; normals by its
// octahedral map at 10 bits, [−1, 1] in 1022 steps (δ = 1/1022); UVs over [0, 1] in 2¹² − 1 steps.
// Half a step each.
TEST(GltfCompression, DracoLoadsAsThePlainFile) {
  test::TempDir dir;
  Warnings w;
  const Mesh plain = load_mesh(write_plain(dir), w);
  const Mesh packed = load_mesh(write_draco(dir), w);
  expect_same_triangles(plain, packed,
                        {2 * kRadius / 16383 / 2 * 1.01f + 1e-6f, kOctahedralGain / 1022, 0.5f / 4095 * 1.01f + 1e-6f});
}

TEST(GltfCompression, BrokenStreamsAreRefusedWithTheirPath) {
  test::TempDir dir;
  Warnings w;
  auto error_of = [&](const std::string& file, const std::function<void(std::string&)>& damage) {
    std::ifstream in(file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    damage(bytes);
    std::ofstream(dir.file("bad.glb"), std::ios::binary) << bytes;
    try {
      load_mesh(dir.file("bad.glb"), w);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // The bitstream's magic number spoiled.
  const std::string draco = write_draco(dir);
  const std::string cut = error_of(draco, [](std::string& b) { b.replace(b.find("DRACO"), 5, "DRACA"); });
  EXPECT_NE(cut.find("bad.glb: $.meshes[0].primitives[0].extensions.KHR_draco_mesh_compression: Draco cannot decode"),
            std::string::npos)
      << cut;
  // The meshopt index stream's count cut to 9 (three triangles): the codec finds bytes left over.
  const std::string meshopt = write_meshopt(dir);
  const std::string count = std::to_string(sphere().idx.size());
  const std::string longer = error_of(meshopt, [&](std::string& b) {
    const std::size_t at = b.find("\"count\":" + count + ",\"filter\"");
    b.replace(at, 8 + count.size(), "\"count\":" + std::string(count.size() - 1, ' ') + "9");
  });
  EXPECT_NE(longer.find("bad.glb: $.bufferViews[3].extensions.EXT_meshopt_compression"), std::string::npos) << longer;
}

// export-blender writes a decompressed copy of a compressed object beside its script, since
// Blender 3.4's importer has neither decoder: the copy loads as the compressed file does, without
// the extensions; a plain file is imported from where it is. Where Blender is installed (CI
// installs it), Blender imports the copy with every triangle.
TEST(GltfCompression, ExportBlenderCarriesADecompressedCopy) {
  test::SceneFixture fx;
  const test::TempDir& dir = fx.dir;
  Warnings w;
  EXPECT_FALSE(gltf_plain_copy(write_plain(dir)).has_value());
  for (const char* kind : {"draco", "meshopt"}) {
    const std::string packed = kind == std::string("draco") ? write_draco(dir) : write_meshopt(dir);
    fx.scene["objects"] = {{{"mesh", packed}}};
    const test::CliRun r = test::run_insitu(dir, "export-blender " + fx.write() + " -o " + dir.file("x.py"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string copy = dir.file("x.objects0.glb");
    EXPECT_NE(r.out.find(copy), std::string::npos) << r.out;
    EXPECT_NE(test::slurp(dir.file("x.py")).find("data_file(\"x.objects0.glb\""), std::string::npos) << kind;
    const std::string bytes = test::slurp(copy);
    EXPECT_EQ(bytes.find("_compression"), std::string::npos) << kind;
    const Mesh original = load_mesh(packed, w), plain = load_mesh(copy, w);
    EXPECT_EQ(plain.positions, original.positions) << kind;
    EXPECT_EQ(plain.normals, original.normals) << kind;
    EXPECT_EQ(plain.triangles.size(), original.triangles.size()) << kind;
    if (std::system("command -v blender > /dev/null 2>&1") != 0) continue;
    const std::string py =
        dir.write("count.py",
                  "import bpy, numpy\n"
                  "numpy.bool = bool\n"  // Debian's Blender 3.4 importer and NumPy 1.24
                  "bpy.ops.wm.read_factory_settings(use_empty=True)\n"
                  "bpy.ops.import_scene.gltf(filepath='" +
                      copy +
                      "')\n"
                      "print('TRIANGLES', sum(len(o.data.polygons) for o in bpy.data.objects if o.type == 'MESH'))\n");
    const std::string out = dir.file("blender.txt");
    ASSERT_EQ(std::system(("blender -b --factory-startup --python " + py + " > " + out + " 2>&1").c_str()), 0);
    EXPECT_NE(test::slurp(out).find("TRIANGLES " + std::to_string(sphere().idx.size() / 3)), std::string::npos)
        << test::slurp(out);
  }
}

}  // namespace
}  // namespace insitu
