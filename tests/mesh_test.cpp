#include <gtest/gtest.h>

#include <filesystem>

#include "render/embree_scene.h"
#include "render/mesh.h"
#include "scene/scene_file.h"
#include "test_util.h"

namespace insitu {
namespace {

using test::test_data;

TEST(Mesh, GoodQuadWithMaterial) {
  Warnings w;
  const Mesh m = load_obj(test_data("good_quad.obj"), w);
  EXPECT_TRUE(w.items.empty()) << w.items.front();
  ASSERT_EQ(m.triangles.size(), 2u);                    // the quad is fanned
  EXPECT_EQ(m.triangles[0].v[0], m.triangles[1].v[0]);  // a fan about the first corner: (1 2 3), (1 3 4)
  EXPECT_EQ(m.triangles[0].v[2], m.triangles[1].v[1]);
  // The files it was read from: the OBJ and the MTL it names (inputs no output may replace).
  ASSERT_EQ(m.files.size(), 2u);
  EXPECT_EQ(std::filesystem::path(m.files[1]).filename(), "good_quad.mtl");
  ASSERT_GE(m.materials.size(), 1u);
  const Material& red = m.materials[m.triangles[0].material];
  EXPECT_EQ(red.name, "red");
  EXPECT_TRUE(red.kd.isApprox(Rgb(0.8f, 0.1f, 0.05f)));
  EXPECT_TRUE(red.ks.isApprox(Rgb(0.04f, 0.04f, 0.04f)));
  EXPECT_FLOAT_EQ(red.ns, 50.0f);
  EXPECT_FALSE(red.cutout());  // no `d`: opaque
  for (const Triangle& t : m.triangles)
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(t.n[c], 0);
      EXPECT_GE(t.t[c], 0);
    }
}

struct BadCase {
  const char* file;
  const char* where;    // expected location suffix
  const char* message;  // expected part of the message
};

class BadObj : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadObj, ErrorNamesFileAndLine) {
  const BadCase& c = GetParam();
  Warnings w;
  try {
    load_obj(test_data(c.file), w);
    FAIL() << "expected an InputError for " << c.file;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), test_data(c.file) + c.where) << e.what();
    EXPECT_NE(e.message().find(c.message), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Files, BadObj,
    ::testing::Values(BadCase{"bad_nan_vertex.obj", ":3", "'nan' is not a finite number"},
                      BadCase{"bad_zero_index.obj", ":5", "face vertex index 0"},
                      BadCase{"bad_index_range.obj", ":4", "face vertex index 7 out of range (3 defined so far)"},
                      BadCase{"bad_two_vertex_face.obj", ":4", "face has 2 vertices"},
                      BadCase{"bad_vertex_text.obj", ":2", "'zero' is not a number"},
                      BadCase{"bad_short_vertex.obj", ":2", "vertex needs 3 numbers, has 2"},
                      BadCase{"bad_normal_index.obj", ":5", "face normal index 2 out of range"},
                      // Found by the OBJ fuzzer: "v\r0 …" is a vertex to the scan, not to tinyobjloader.
                      BadCase{"bad_cr_after_keyword.obj", ":4", "face index out of range"},
                      BadCase{"no_faces.obj", "", "no triangles"}, BadCase{"no_such_file.obj", "", "not found"}),
    [](const auto& p) {
      std::string n = p.param.file;
      for (auto& ch : n)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return n;
    });

TEST(Mesh, MissingTextureNamesMaterialAndTexture) {
  Warnings w;
  try {
    load_obj(test_data("missing_texture.obj"), w);
    FAIL();
  } catch (const InputError& e) {
    const std::string s = e.what();
    EXPECT_NE(s.find("missing_texture.obj: material 'tex': map_Kd"), std::string::npos) << s;
    EXPECT_NE(s.find("no_such_texture.png: file not found"), std::string::npos) << s;
  }
}

TEST(Mesh, DegenerateTrianglesAreDroppedAndCounted) {
  Warnings w;
  const Mesh m = load_obj(test_data("degenerate.obj"), w);
  EXPECT_EQ(m.triangles.size(), 1u);
  ASSERT_EQ(w.items.size(), 1u);
  EXPECT_NE(w.items[0].find("1 degenerate triangle(s) dropped (first at line 5)"), std::string::npos) << w.items[0];
}

// 10⁵ copies of one triangle (other vertex indices, other windings, other first corners) are one
// surface: the mesh keeps the quad's two triangles and says how many it dropped, and where.
TEST(Mesh, CopiesOfATriangleAreDroppedAndCounted) {
  test::TempDir dir;
  std::string obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 0 0\nf 1 2 3\nf 1 3 4\n";  // lines 6, 7
  const char* copies[] = {"f 1 2 3\n", "f 3 2 1\n", "f 2 3 1\n", "f 1 5 3\n"};          // v 5 is v 2's position
  for (int i = 0; i < 100000; ++i) obj += copies[i % 4];
  Warnings w;
  const Mesh m = load_obj(dir.write("copies.obj", obj), w);
  EXPECT_EQ(m.triangles.size(), 2u);
  ASSERT_EQ(w.items.size(), 1u);
  EXPECT_NE(w.items[0].find("100000 triangle(s) dropped that repeat another's three corners exactly (first at line 8)"),
            std::string::npos)
      << w.items[0];
}

TEST(Mesh, RelativeIndices) {
  Warnings w;
  const Mesh m = load_obj(test_data("relative_indices.obj"), w);
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.triangles[0].v, (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m.triangles[1].v, (std::array<std::uint32_t, 3>{0, 1, 3}));
}

TEST(Mesh, TransformMovesPositionsAndNormals) {
  Warnings w;
  Mesh m = load_obj(test_data("good_quad.obj"), w);
  // Rotate 90° about X (the +Y normal turns to +Z), scale 2 along y (normals use the inverse
  // transpose), translate by (1, 2, 3).
  const Mat4d M = object_transform({1, 2, 3}, 90.0, {1, 0, 0}, {2, 2, 2});
  transform_mesh(m, M);
  EXPECT_TRUE(m.positions[1].isApprox(Vec3f(3, 2, 3), 1e-5f));
  EXPECT_TRUE(m.normals[0].isApprox(Vec3f(0, 0, 1), 1e-5f));
}

TEST(Mesh, EmbreeHitsTheQuadWhereExpected) {
  Warnings w;
  std::vector<Mesh> meshes;
  meshes.push_back(load_obj(test_data("good_quad.obj"), w));
  const EmbreeScene scene(std::move(meshes));
  // A ray straight down through (0.25, 5, −0.75) hits at t = 5 with uv (0.25, 0.75).
  const Ray ray{{0.25f, 5.0f, -0.75f}, {0, -1, 0}};
  const Hit hit = scene.intersect(ray);
  ASSERT_TRUE(hit.valid());
  EXPECT_NEAR(hit.t, 5.0f, 1e-5f);
  const SurfacePoint sp = scene.surface(ray, hit);
  EXPECT_TRUE(sp.p_world.isApprox(Vec3f(0.25f, 0, -0.75f), 1e-5f));
  EXPECT_TRUE(sp.uv[0].isApprox(Vec2f(0.25f, 0.75f), 1e-5f));
  EXPECT_TRUE(sp.ns_world.isApprox(Vec3f(0, 1, 0), 1e-5f));
  // From below: two-sided, both normals face the ray.
  const Ray up{{0.25f, -5.0f, -0.75f}, {0, 1, 0}};
  const SurfacePoint below = scene.surface(up, scene.intersect(up));
  EXPECT_TRUE(below.ns_world.isApprox(Vec3f(0, -1, 0), 1e-5f));
  EXPECT_TRUE(below.ng_world.isApprox(Vec3f(0, -1, 0), 1e-5f));
  // A miss.
  EXPECT_FALSE(scene.intersect({{2.0f, 5.0f, 0.0f}, {0, -1, 0}}).valid());
}

TEST(Mesh, SharedMeshesLoad) {
  INSITU_REQUIRE_SHARED();
  Warnings w;
  const Mesh bunny = load_obj(test::shared_data() + "/models/bunny.obj", w);
  EXPECT_EQ(bunny.triangles.size(), 5648u);  // ../shared/data/models/README.txt
  EXPECT_EQ(bunny.positions.size(), 2826u);
  const Bounds b = mesh_bounds(bunny);
  EXPECT_NEAR(b.lo.x(), -0.913771f, 1e-5f);
  EXPECT_NEAR(b.hi.y(), 0.939832f, 1e-5f);
  const Mesh suzanne = load_obj(test::shared_data() + "/models/suzanne.obj", w);
  EXPECT_EQ(suzanne.triangles.size(), 14842u);
  EXPECT_TRUE(w.items.empty());
}

}  // namespace
}  // namespace insitu
