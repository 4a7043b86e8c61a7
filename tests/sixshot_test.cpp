#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "environment.h"
#include "equirect.h"
#include "scene.h"
#include "sixshot.h"
#include "test_util.h"

namespace insitu {
namespace {

// The shots a phone would take, written from DESIGN.md's words rather than from sixshot.cpp:
// a wall shot looks along its wall's axis with +Y up; the ceiling shot looks up with its bottom
// edge toward the faced wall W (so "up" in the picture is −W); the floor shot looks down with its
// top edge toward W (up is +W). Right is forward × up; pixel (x, y) looks along
// forward + right·(2(x+0.5)/n − 1) − up·(2(y+0.5)/n − 1) for a 90° square shot.
Image phone_shot(const Image& equirect, const Vec3f& forward, const Vec3f& up, int n) {
  const Vec3f right = forward.cross(up);
  Image img(n, n, 3);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float a = 2.0f * (float(x) + 0.5f) / float(n) - 1.0f, b = 2.0f * (float(y) + 0.5f) / float(n) - 1.0f;
      img.set_rgb(x, y, equirect_lookup(equirect, (forward + a * right - b * up).normalized()));
    }
  return img;
}

Vec3f axis_of(int face) {
  static const Vec3f axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  return axes[face];
}

ShotSet phone_shots(const Image& equirect, int faced, int n) {
  ShotSet set;
  set.faced_face = faced;
  const Vec3f W = axis_of(faced), Y(0, 1, 0);
  for (int f : {kPosX, kNegX, kPosZ, kNegZ}) set.shots[f] = phone_shot(equirect, axis_of(f), Y, n);
  set.shots[kPosY] = phone_shot(equirect, Y, -W, n);
  set.shots[kNegY] = phone_shot(equirect, -Y, W, n);
  for (int f = 0; f < 6; ++f) set.names[f] = face_name(f);
  return set;
}

// The environment's own cube: each texel the equirect sampled at the texel centre.
CubeMap reference_cube(const Image& equirect, int n) { return cube_from_equirect(equirect, n, 1); }

double max_relative_error(const CubeMap& a, const CubeMap& b) {
  double worst = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < a.size(); ++j)
      for (int i = 0; i < a.size(); ++i) {
        const Rgb x = a.texel(f, i, j), y = b.texel(f, i, j);
        worst = std::max(worst, double((x - y).abs().maxCoeff() / (y.abs().maxCoeff() + 1e-3f)));
      }
  return worst;
}

class SixShotFaced : public ::testing::TestWithParam<int> {};

// Shots made from a real HDRI, reassembled, match the HDRI's own cube for every faced wall. With
// 90° shots of the face's size every texel centre is a pixel centre, so the only error is the
// float rounding of the bilinear weights.
TEST_P(SixShotFaced, ReassemblesTheEnvironment) {
  INSITU_REQUIRE_SHARED();
  const Image env = linearize(read_image_file(test::shared_data() + "/hdri/interior.exr"));
  const int n = 32, faced = GetParam();
  const CubeMap cube = assemble_cube(phone_shots(env, faced, n), n);
  EXPECT_LT(max_relative_error(cube, reference_cube(env, n)), 2e-3);
}

INSTANTIATE_TEST_SUITE_P(EveryFacedWall, SixShotFaced, ::testing::Values(kPosX, kNegX, kPosZ, kNegZ),
                         [](const auto& p) { return std::string("faced_") + (p.param == kPosX ? "px" : p.param == kNegX ? "nx" : p.param == kPosZ ? "pz" : "nz"); });

// The same through the scene file's front/right/back/left form: shots written as EXR files,
// front given by front_axis, the faced wall named "front" / "right" / "back" / "left".
TEST(SixShot, FrontRightBackLeftFormInTheSceneFile) {
  INSITU_REQUIRE_SHARED();
  const Image env = linearize(read_image_file(test::shared_data() + "/hdri/apartment.exr"));
  const int n = 24;
  test::TempDir dir;
  struct Form { const char* front_axis; const char* faced_name; int faced; int walls[4]; };
  // Turning right (clockwise from above): −z → +x → +z → −x.
  const Form forms[] = {{"-z", "front", kNegZ, {kNegZ, kPosX, kPosZ, kNegX}},
                        {"+x", "right", kPosZ, {kPosX, kPosZ, kNegX, kNegZ}},
                        {"+z", "back", kNegZ, {kPosZ, kNegX, kNegZ, kPosX}},
                        {"-x", "left", kPosZ, {kNegX, kNegZ, kPosX, kPosZ}}};
  const CubeMap ref = reference_cube(env, n);
  for (const Form& form : forms) {
    const ShotSet set = phone_shots(env, form.faced, n);
    const char* names[4] = {"front", "right", "back", "left"};
    nlohmann::json shots = {{"front_axis", form.front_axis}, {"faced", form.faced_name}};
    for (int k = 0; k < 4; ++k) {
      write_image(dir.file(std::string(names[k]) + ".exr"), set.shots[form.walls[k]]);
      shots[names[k]] = std::string(names[k]) + ".exr";
    }
    write_image(dir.file("up.exr"), set.shots[kPosY]);
    write_image(dir.file("down.exr"), set.shots[kNegY]);
    shots["up"] = "up.exr";
    shots["down"] = "down.exr";
    write_image(dir.file("photo.png"), Image(8, 8, 3, 0.5f));
    const nlohmann::json scene = {{"photo", "photo.png"},
                                  {"camera", {{"eye", {0, 1, 0}}, {"look", {0, 1, -1}}, {"hfov_deg", 60}}},
                                  {"environment", {{"shots", shots}}}};
    const std::string path = dir.write("scene.json", scene.dump());
    const SceneSpec spec = parse_scene_file(path);
    Warnings w;
    const CubeMap cube = load_environment(spec.environment, w);
    ASSERT_EQ(cube.size(), n);
    EXPECT_LT(max_relative_error(cube, ref), 2e-3) << "front_axis " << form.front_axis << ", faced " << form.faced_name;
  }
}

// Orientation by hand: a photo facing −Z has +X on its right, so its top-right pixel looks along
// (+1, +1, −1); on the −Z face that is sc = −rx = −1, tc = −ry = −1: texel (0, 0). The faces are
// mirrored relative to the photos.
TEST(SixShot, NorthShotIsMirroredOntoItsFace) {
  const int n = 4;
  ShotSet set;
  set.faced_face = kNegZ;
  for (int f = 0; f < 6; ++f) { set.shots[f] = Image(n, n, 3, 0.0f); set.names[f] = face_name(f); }
  set.shots[kNegZ].set_rgb(n - 1, 0, Rgb(1, 2, 3));  // top-right pixel of the north photo
  const CubeMap cube = assemble_cube(set, n);
  EXPECT_TRUE(cube.texel(kNegZ, 0, 0).isApprox(Rgb(1, 2, 3)));
  EXPECT_FLOAT_EQ(cube.texel(kNegZ, n - 1, 0)[0], 0.0f);
  // Ceiling shot, faced wall −Z: its bottom edge points to −Z, so its top-left pixel looks along
  // (−1, +1, +1) (left = −X, top = away from the faced wall = +Z); on +Y that is
  // sc = rx = −1, tc = rz = +1: texel (0, n−1).
  set.shots[kPosY].set_rgb(0, 0, Rgb(5, 5, 5));
  const CubeMap cube2 = assemble_cube(set, n);
  EXPECT_FLOAT_EQ(cube2.texel(kPosY, 0, n - 1)[0], 5.0f);
}

TEST(SixShot, LargeShotsAreFilteredDownToTheFace) {
  // A 4096² shot of a constant radiance onto a 16² face stays that constant (through OIIO resize).
  ShotSet set;
  for (int f = 0; f < 6; ++f) { set.shots[f] = Image(f == 0 ? 4096 : 16, f == 0 ? 4096 : 16, 3, 0.25f); set.names[f] = face_name(f); }
  EXPECT_EQ(natural_face_size(set), 16);
  const CubeMap cube = assemble_cube(set, 16);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) EXPECT_NEAR(cube.texel(kPosX, i, j)[0], 0.25f, 1e-6f);
}

TEST(SixShot, NonSquareOrNarrowShotsAreErrorsNamingTheShot) {
  ShotSet set;
  for (int f = 0; f < 6; ++f) { set.shots[f] = Image(8, 8, 3, 1.0f); set.names[f] = std::string("shot") + face_name(f) + ".jpg"; }
  set.shots[kPosZ] = Image(8, 6, 3, 1.0f);
  try {
    assemble_cube(set, 8);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "shot+z.jpg");
    EXPECT_NE(e.message().find("not square"), std::string::npos);
  }
  set.shots[kPosZ] = Image(8, 8, 3, 1.0f);
  set.hfov_deg = 60;
  EXPECT_THROW(assemble_cube(set, 8), InputError);
}

}  // namespace
}  // namespace insitu
