#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "light/environment.h"
#include "light/equirect.h"
#include "scene/scene_file.h"
#include "light/sixshot.h"
#include "test_util.h"

#include <random>

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
                         [](const auto& p) {
                           return std::string("faced_") + (p.param == kPosX   ? "px"
                                                           : p.param == kNegX ? "nx"
                                                           : p.param == kPosZ ? "pz"
                                                                              : "nz");
                         });

// The same through the scene file's front/right/back/left form: shots written as EXR files,
// front given by front_axis, the faced wall named "front" / "right" / "back" / "left".
TEST(SixShot, FrontRightBackLeftFormInTheSceneFile) {
  INSITU_REQUIRE_SHARED();
  const Image env = linearize(read_image_file(test::shared_data() + "/hdri/apartment.exr"));
  const int n = 24;
  test::TempDir dir;
  struct Form {
    const char* front_axis;
    const char* faced_name;
    int faced;
    int walls[4];
  };
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
  for (int f = 0; f < 6; ++f) {
    set.shots[f] = Image(n, n, 3, 0.0f);
    set.names[f] = face_name(f);
  }
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
  for (int f = 0; f < 6; ++f) {
    set.shots[f] = Image(f == 0 ? 4096 : 16, f == 0 ? 4096 : 16, 3, 0.25f);
    set.names[f] = face_name(f);
  }
  EXPECT_EQ(natural_face_size(set), 16);
  const CubeMap cube = assemble_cube(set, 16);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) EXPECT_NEAR(cube.texel(kPosX, i, j)[0], 0.25f, 1e-6f);
}

// Non-square shots with other fields of view, made from a real HDRI: where a shot covers its face
// the cube matches the environment's own within interpolation error; the rest is filled.
TEST(SixShot, NonSquareAndNarrowShotsAreReprojectedAndFilled) {
  INSITU_REQUIRE_SHARED();
  const Image env = linearize(read_image_file(test::shared_data() + "/hdri/apartment.exr"));
  const int n = 32;
  ShotSet set;
  set.faced_face = kNegZ;
  const Vec3f W = axis_of(kNegZ), Y(0, 1, 0);
  // Landscape 4:3 shots with 110° (covers the face: vertical fov 2·atan(0.75·tan 55°) = 94°) and a
  // 75° one on +Z that leaves a border uncovered.
  auto shot = [&](const Vec3f& fwd, const Vec3f& up, double hfov, int w, int h) {
    const Vec3f right = fwd.cross(up);
    const double f_px = 0.5 * w / std::tan(0.5 * deg_to_rad(hfov));
    Image img(w, h, 3);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float a = float((x + 0.5 - 0.5 * w) / f_px), b = float((y + 0.5 - 0.5 * h) / f_px);
        img.set_rgb(x, y, equirect_lookup(env, (fwd + a * right - b * up).normalized()));
      }
    return img;
  };
  for (int f : {kPosX, kNegX, kNegZ}) set.shots[std::size_t(f)] = shot(axis_of(f), Y, 110, 160, 120);
  set.shots[kPosY] = shot(Y, -W, 110, 160, 120);
  set.shots[kNegY] = shot(-Y, W, 110, 160, 120);
  set.shots[kPosZ] = shot(axis_of(kPosZ), Y, 75, 96, 72);
  for (int f = 0; f < 6; ++f) set.names[std::size_t(f)] = face_name(f);
  for (int f = 0; f < 6; ++f) set.hfov_deg[std::size_t(f)] = f == kPosZ ? 75 : 110;
  AssemblyInfo info;
  const CubeMap cube = assemble_cube(set, n, &info);
  EXPECT_DOUBLE_EQ(info.coverage[kPosX], 1.0);
  // +Z's 75° shot (2·atan(0.75·tan 37.5°) = 59° vertical) covers tan 37.5° × tan 29.9° of its face;
  // the 110° shots of its neighbours reach into it as well. A texel is covered when any shot's
  // frustum holds its direction.
  const auto frustum_holds = [&](const Vec3f& fwd, const Vec3f& up, double hfov, double aspect, const Vec3f& d) {
    const Vec3f right = fwd.cross(up);
    const double z = d.dot(fwd), t = std::tan(0.5 * deg_to_rad(hfov));
    return z > 0 && std::abs(d.dot(right) / z) <= t && std::abs(d.dot(up) / z) <= t * aspect;
  };
  long covered = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec3f d = texel_direction(kPosZ, i, j, n);
      bool any = frustum_holds(axis_of(kPosZ), Y, 75, 0.75, d) || frustum_holds(Y, -W, 110, 0.75, d) ||
                 frustum_holds(-Y, W, 110, 0.75, d);
      for (int f : {kPosX, kNegX, kNegZ}) any = any || frustum_holds(axis_of(f), Y, 110, 0.75, d);
      covered += any;
    }
  EXPECT_NEAR(info.coverage[kPosZ], double(covered) / (n * n), 2.0 / n);
  EXPECT_LT(info.coverage[kPosZ], 1.0);
  // The shots are area-averaged onto the texels, so the reference is too (4×4 samples per texel).
  const CubeMap ref = cube_from_equirect(env, n, 4);
  // Covered texels: filtering and interpolation differences only.
  double err = 0, norm = 0;
  for (int f : {kPosX, kNegX, kNegZ, kPosY, kNegY})
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        err += std::abs(luminance(cube.texel(f, i, j)) - luminance(ref.texel(f, i, j)));
        norm += luminance(ref.texel(f, i, j));
      }
  EXPECT_LT(err / norm, 0.05);
  EXPECT_TRUE(cube.texel(kPosZ, 0, 0).allFinite());
}

// The fill of a constant is that constant; the fill of anything stays within the known range.
TEST(SixShot, FillIsSmoothAndBounded) {
  const int n = 16;
  CubeMap c(n), w(n);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0, 1);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const bool known = (i > 4 && i < 11 && j > 4 && j < 11) || f == kPosX;
        c.set_texel(f, i, j, known ? Rgb::Constant(2.5f) : Rgb::Constant(-99.0f));
        w.set_texel(f, i, j, Rgb::Constant(known ? 1.0f : 0.0f));
      }
  c.update_borders();
  w.update_borders();
  CubeMap constant = c;
  fill_uncovered(constant, w);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) ASSERT_NEAR(constant.texel(f, i, j)[0], 2.5f, 1e-5f);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (w.texel(f, i, j)[0] > 0) c.set_texel(f, i, j, Rgb::Constant(1 + u(rng)));
  c.update_borders();
  fill_uncovered(c, w);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        ASSERT_GE(c.texel(f, i, j)[0], 1.0f - 1e-5f);
        ASSERT_LE(c.texel(f, i, j)[0], 2.0f + 1e-5f);
      }
}

// Narrow shots (70°, 4:3: the main camera) every pixel of which clipped: the texels a shot saw are
// clipped, those none saw are filled in radiance but not clipped (their fill is no lower bound of
// anything: inverse lighting must not scale them).
TEST(SixShot, TexelsNoShotSawAreFilledButNotClipped) {
  ShotSet set, clipped;
  set.set_hfov(70);
  clipped.set_hfov(70);
  for (int s = 0; s < 6; ++s) {
    set.shots[std::size_t(s)] = Image(40, 30, 3, 1.0f);
    clipped.shots[std::size_t(s)] = Image(40, 30, 3, 1.0f);
    set.names[std::size_t(s)] = clipped.names[std::size_t(s)] = face_name(s);
  }
  const int n = 32;
  CubeMap clip_cube;
  AssemblyInfo info;
  const CubeMap cube = assemble_cube(set, n, &info, &clipped, &clip_cube);
  ASSERT_LT(info.coverage[kPosX], 0.6);
  int seen = 0, unseen = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        ASSERT_NEAR(cube.texel(f, i, j)[0], 1.0f, 1e-5f);  // the fill of a constant
        const float c = clip_cube.texel(f, i, j)[0];
        ASSERT_TRUE(c == 0.0f || c == 1.0f) << c;
        (c == 1.0f ? seen : unseen) += 1;
      }
  // The face's centre is seen, its corner is not.
  EXPECT_EQ(clip_cube.texel(kPosX, n / 2, n / 2)[0], 1.0f);
  EXPECT_EQ(clip_cube.texel(kPosX, 0, 0)[0], 0.0f);
  EXPECT_NEAR(double(seen) / (6.0 * n * n), info.coverage[kPosX], 0.02);
  EXPECT_GT(unseen, 0);
}

TEST(SixShot, AShotThatCoversNothingIsAnErrorNamingIt) {
  ShotSet set;
  for (int f = 0; f < 6; ++f) {
    set.shots[std::size_t(f)] = Image(8, 8, 3, 1.0f);
    set.names[std::size_t(f)] = std::string("shot") + face_name(f) + ".jpg";
  }
  set.hfov_deg[kPosZ] = 0.5;  // a pinhole's worth: no texel centre falls inside
  try {
    assemble_cube(set, 8);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "shot+z.jpg");
  }
}

// A phone turned on its side stores the shot turned: here each landscape shot is stored turned a
// quarter counter-clockwise (pixel (x, y) of a w-wide image goes to (y, w − 1 − x)) k times, and
// "rotate_deg": 90·k turns it back. "hfov_deg" is across the stored width, so the file turned a
// quarter gives the field across its 120 pixels: 2·atan(tan 50° · 120/160). The cube must equal
// the one from the unturned shots: the turn is a permutation of pixels.
Image turned_counter_clockwise(const Image& img, int quarters) {
  Image out = img;
  for (int q = 0; q < quarters; ++q) {
    Image next(out.height, out.width, out.channels);
    for (int y = 0; y < out.height; ++y)
      for (int x = 0; x < out.width; ++x) next.set_rgb(y, out.width - 1 - x, out.rgb(x, y));
    out = next;
  }
  return out;
}

TEST(SixShot, TurnedShotsAreTurnedBackWithTheirFieldOfView) {
  test::TempDir dir;
  auto radiance = [](const Vec3f& d) { return Rgb(1.5f + d.x(), 1.2f + 0.8f * d.y(), 1.1f + d.z() * d.x()); };
  const double hfov_deg = 100;
  const char* keys[6] = {"+x", "-x", "up", "down", "+z", "-z"};
  nlohmann::json plain = {{"faced", "-z"}}, turned = {{"faced", "-z"}};
  for (int f = 0; f < 6; ++f) {
    const Image shot = render_shot(radiance, f, kNegZ, hfov_deg, 160, 120);
    const int k = f % 4;  // every turn, and one of each twice
    const std::string a = std::string("plain") + std::to_string(f) + ".exr",
                      b = std::string("turned") + std::to_string(f) + ".exr";
    write_image(dir.file(a), shot);
    write_image(dir.file(b), turned_counter_clockwise(shot, k));
    plain[keys[f]] = {{"file", a}, {"hfov_deg", hfov_deg}};
    const double stored_hfov_deg =
        k % 2 ? rad_to_deg(2 * std::atan(std::tan(deg_to_rad(0.5 * hfov_deg)) * 120 / 160)) : hfov_deg;
    turned[keys[f]] = {{"file", b}, {"hfov_deg", stored_hfov_deg}, {"rotate_deg", 90 * k}};
  }
  write_image(dir.file("photo.png"), Image(8, 8, 3, 0.5f));
  auto cube_of = [&](const nlohmann::json& shots) {
    const nlohmann::json scene = {{"photo", "photo.png"},
                                  {"camera", {{"eye", {0, 1, 0}}, {"look", {0, 1, -1}}, {"hfov_deg", 60}}},
                                  {"environment", {{"shots", shots}, {"face_size", 32}}}};
    Warnings w;
    return load_environment(parse_scene_file(dir.write("scene.json", scene.dump())).environment, w);
  };
  const CubeMap want = cube_of(plain), got = cube_of(turned);
  EXPECT_LT(max_relative_error(got, want), 1e-5);
  // And the unturned shots are the radiance, filtered onto the face (coverage is full at 100°).
  CubeMap truth(32);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < 32; ++j)
      for (int i = 0; i < 32; ++i) truth.set_texel(f, i, j, radiance(texel_direction(f, i, j, 32)));
  EXPECT_LT(max_relative_error(want, truth), 0.02);
}

TEST(SixShot, ARotationOtherThanAQuarterTurnIsAnErrorNamingIt) {
  test::TempDir dir;
  write_image(dir.file("s.exr"), Image(8, 8, 3, 1.0f));
  write_image(dir.file("photo.png"), Image(8, 8, 3, 0.5f));
  nlohmann::json shots = {{"faced", "-z"}};
  for (const char* k : {"+x", "-x", "up", "down", "+z", "-z"}) shots[k] = "s.exr";
  shots["+z"] = {{"file", "s.exr"}, {"rotate_deg", 45}};
  const nlohmann::json scene = {{"photo", "photo.png"},
                                {"camera", {{"eye", {0, 1, 0}}, {"look", {0, 1, -1}}, {"hfov_deg", 60}}},
                                {"environment", {{"shots", shots}}}};
  const std::string path = dir.write("scene.json", scene.dump());
  try {
    parse_scene_file(path);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), path + ":$.environment.shots.+z.rotate_deg");
    EXPECT_NE(std::string(e.what()).find("90"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace insitu
