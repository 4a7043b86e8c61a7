// The demo's catalogue asset (scenes/demo/chair.glb, written by tools/demo_chair.cpp) as the glTF
// loader reads it: the four material classes a catalogue sells, each with what makes it that class,
// the side table placed by its node beside the chair, everything on the floor, and a glass top
// that is a closed solid (its absorption is applied between a front face and a back face).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <tuple>

#include "render/gltf_mesh.h"
#include "test_util.h"

namespace insitu {
namespace {

const Mesh& demo_chair() {
  static const Mesh mesh = [] {
    Warnings warnings;
    Mesh m = load_gltf(test::source_dir() + "/scenes/demo/chair.glb", warnings);
    EXPECT_TRUE(warnings.items.empty()) << "the generated asset has nothing to warn about";
    return m;
  }();
  return mesh;
}

int chair_material(const std::string& name) {
  const auto& ms = demo_chair().materials;
  for (std::size_t i = 0; i < ms.size(); ++i)
    if (ms[i].name == name) return int(i);
  ADD_FAILURE() << "no material " << name;
  return 0;
}

TEST(DemoChair, CarriesTheFourCatalogueMaterials) {
  const auto& ms = demo_chair().materials;
  const Material& walnut = ms[std::size_t(chair_material("lacquered walnut"))];
  EXPECT_TRUE(walnut.principled && walnut.map_kd && walnut.map_normal);
  EXPECT_GT(walnut.clearcoat, 0.5f);
  EXPECT_LT(walnut.clearcoat_roughness, walnut.roughness);  // a gloss over a rougher base
  const Material& velvet = ms[std::size_t(chair_material("rust velvet"))];
  EXPECT_GT(velvet.sheen.maxCoeff(), velvet.kd.maxCoeff());  // a pale sheen over a dark base
  const Material& steel = ms[std::size_t(chair_material("brushed steel"))];
  EXPECT_EQ(steel.metallic, 1.0f);
  const Material& glass = ms[std::size_t(chair_material("tinted glass"))];
  EXPECT_EQ(glass.transmission, 1.0f);
  // A green-cyan tint: red absorbed most, green least, all finite and positive.
  EXPECT_GT(glass.absorption[0], glass.absorption[2]);
  EXPECT_GT(glass.absorption[2], glass.absorption[1]);
  EXPECT_GT(glass.absorption[1], 0.0f);
  EXPECT_FALSE(demo_chair().tangents.empty()) << "MikkTSpace tangents for the walnut's normal map";
}

TEST(DemoChair, StandsOnTheFloorWithTheTableBesideIt) {
  const Mesh& mesh = demo_chair();
  const int glass = chair_material("tinted glass");
  float y_min = 1e9f, chair_x_max = -1e9f, glass_x_min = 1e9f;
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t v : t.v) {
      const Vec3f& p = mesh.positions[v];
      y_min = std::min(y_min, p.y());
      if (t.material == glass)
        glass_x_min = std::min(glass_x_min, p.x());
      else if (p.y() > 0.6f)  // the chair's arms and back: the table is lower
        chair_x_max = std::max(chair_x_max, p.x());
    }
  EXPECT_NEAR(y_min, 0.0f, 1e-5f);
  EXPECT_GT(glass_x_min, chair_x_max) << "the side table's node places it to the chair's right";
}

TEST(DemoChair, TheGlassTopIsAClosedSolid) {
  // Every edge (by its corners' positions) is shared by exactly two of the glass's triangles, once
  // in each direction: closed and consistently wound.
  const Mesh& mesh = demo_chair();
  const int glass = chair_material("tinted glass");
  auto key = [&](std::uint32_t i) {
    const Vec3f& p = mesh.positions[i];
    return std::make_tuple(p.x(), p.y(), p.z());
  };
  std::map<std::pair<std::tuple<float, float, float>, std::tuple<float, float, float>>, int> directed;
  int triangles = 0;
  for (const Triangle& t : mesh.triangles) {
    if (t.material != glass) continue;
    ++triangles;
    for (int k = 0; k < 3; ++k) ++directed[{key(t.v[std::size_t(k)]), key(t.v[std::size_t((k + 1) % 3)])}];
  }
  ASSERT_GT(triangles, 12);
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    const auto reverse = directed.find({edge.second, edge.first});
    EXPECT_TRUE(reverse != directed.end() && reverse->second == 1) << "an open or inconsistently wound edge";
  }
}

}  // namespace
}  // namespace insitu
