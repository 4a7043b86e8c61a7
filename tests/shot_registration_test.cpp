// Registration of the shots (light/shot_registration.h) and their feathered, clip-aware blend
// (light/sixshot.h): known misaims recovered from overlapping views, and what the cube gains.
#include <gtest/gtest.h>

#include <random>

#include <nlohmann/json.hpp>

#include "light/environment.h"
#include "light/equirect.h"
#include "light/shot_features.h"
#include "light/shot_gains.h"
#include "light/shot_registration.h"
#include "light/sixshot.h"
#include "scene/scene_file.h"
#include "handheld_shots.h"
#include "test_util.h"

namespace insitu {
namespace {

using test::angle_deg;
using test::feature_world;
using test::handheld_shots;
using test::mean_relative_error;
using test::misaims;

// The ultra-wide case: 110° shots, each overlapping its four neighbours. Every aim is recovered
// within 0.5° (the goal where shots overlap), and the residual is a fraction of a degree.
TEST(ShotRegistration, RecoversKnownMisaimsFromOverlappingViews) {
  const Image world = feature_world(7);
  const std::array<Mat3d, 6> truth = misaims(11);
  const ShotSet set = handheld_shots(world, truth, 110, 800, 600);
  const Registration r = register_shots(set);
  EXPECT_TRUE(r.overlap);
  for (int s = 0; s < 6; ++s) {
    const ShotAim& a = r.shots[std::size_t(s)];
    EXPECT_TRUE(a.registered) << face_name(s) << ": " << a.reason;
    EXPECT_GE(a.matches, 15) << face_name(s);
    EXPECT_LT(a.residual_deg, 0.3) << face_name(s);
    EXPECT_LT(angle_deg(r.aim[std::size_t(s)], truth[std::size_t(s)]), 0.5)
        << face_name(s) << ": misaimed by " << angle_deg(truth[std::size_t(s)], Mat3d::Identity()) << "°";
    EXPECT_NEAR(a.rotation_deg, angle_deg(truth[std::size_t(s)], Mat3d::Identity()), 0.5) << face_name(s);
  }
}

// What registration buys: the cube assembled with the recovered aims is far nearer the world's
// own cube than the shots pasted at their nominal directions.
TEST(ShotRegistration, TheRegisteredCubeMatchesTheWorld) {
  const Image world = feature_world(5);
  ShotSet set = handheld_shots(world, misaims(3), 110, 800, 600);
  const int n = 96;
  const CubeMap truth = cube_from_equirect(world, n, 4);
  const double nominal = mean_relative_error(assemble_cube(set, n), truth);
  set.aim = register_shots(set).aim;
  const double registered = mean_relative_error(assemble_cube(set, n), truth);
  EXPECT_LT(registered, 0.4 * nominal) << "nominal " << nominal << ", registered " << registered;
}

// 90° shots aimed along the axes tile the cube exactly: nothing overlaps, nothing is tried, and
// every shot says so.
TEST(ShotRegistration, ShotsThatCannotOverlapKeepTheirNominalAims) {
  const Image world = feature_world(2);
  std::array<Mat3d, 6> aligned;
  aligned.fill(Mat3d::Identity());
  const Registration r = register_shots(handheld_shots(world, aligned, 90, 64, 64));
  EXPECT_FALSE(r.overlap);
  for (int s = 0; s < 6; ++s) {
    EXPECT_FALSE(r.shots[std::size_t(s)].registered);
    EXPECT_NE(r.shots[std::size_t(s)].reason.find("overlaps no neighbour"), std::string::npos);
    EXPECT_EQ(r.aim[std::size_t(s)], Mat3d::Identity());
  }
}

// A plain shot (a white wall filling the view) has nothing to match: it is named, with the reason,
// and keeps its nominal aim, while the others register among themselves.
TEST(ShotRegistration, APlainShotIsNamedAndKeptNominal) {
  const Image world = feature_world(9);
  const std::array<Mat3d, 6> truth = misaims(4);
  ShotSet set = handheld_shots(world, truth, 110, 800, 600);
  set.shots[kPosX] = Image(800, 600, 3, 0.7f);
  const Registration r = register_shots(set);
  EXPECT_FALSE(r.shots[kPosX].registered);
  EXPECT_NE(r.shots[kPosX].reason.find("no features"), std::string::npos) << r.shots[kPosX].reason;
  EXPECT_EQ(r.aim[kPosX], Mat3d::Identity());
  for (int s : {kNegX, kPosY, kNegY, kPosZ, kNegZ}) EXPECT_TRUE(r.shots[std::size_t(s)].registered) << face_name(s);
}

// Six 110° shots of constant radiance, +X twice as bright as the rest (an exposure the camera
// changed): across the overlap on the +Z face the blend rises from 1 toward 2 without a step, where
// pasting one shot over another would jump by 1.
TEST(ShotBlending, OverlapsAreFeatheredWithoutASeam) {
  ShotSet set;
  set.set_hfov(110);
  for (int s = 0; s < 6; ++s) {
    set.shots[std::size_t(s)] = Image(44, 33, 3, s == kPosX ? 2.0f : 1.0f);
    set.names[std::size_t(s)] = face_name(s);
  }
  const int n = 64;
  const CubeMap cube = assemble_cube(set, n);
  // The middle row of +Z: its column i = n − 1 touches +X (texel_direction: +Z's s axis is +X).
  const int j = n / 2;
  float max_step = 0;
  for (int i = 1; i < n; ++i)
    max_step = std::max(max_step, std::abs(cube.texel(kPosZ, i, j)[0] - cube.texel(kPosZ, i - 1, j)[0]));
  EXPECT_FLOAT_EQ(cube.texel(kPosZ, n / 2, j)[0], 1.0f);  // only +Z sees the face's centre
  EXPECT_GT(cube.texel(kPosZ, n - 1, j)[0], 1.3f);        // the edge: +X's weight ≈ +Z's
  EXPECT_LT(cube.texel(kPosZ, n - 1, j)[0], 1.7f);
  EXPECT_LT(max_step, 0.1f);
}

// Where one shot clipped and its neighbour did not, the neighbour's radiance is the cube's, and
// the clipped cube says the texel is not clipped.
TEST(ShotBlending, AClippedPixelIsTakenFromANeighbourThatDidNotClip) {
  ShotSet set, clipped;
  set.set_hfov(110);
  clipped.set_hfov(110);
  for (int s = 0; s < 6; ++s) {
    set.shots[std::size_t(s)] = Image(44, 33, 3, s == kPosX ? 1.0f : 5.0f);  // +X clipped at 1
    clipped.shots[std::size_t(s)] = Image(44, 33, 3, s == kPosX ? 1.0f : 0.0f);
    set.names[std::size_t(s)] = clipped.names[std::size_t(s)] = face_name(s);
  }
  const int n = 64;
  CubeMap clip_cube;
  const CubeMap cube = assemble_cube(set, n, nullptr, &clipped, &clip_cube);
  const int i = n - 1, j = n / 2;  // +Z's texel beside +X, seen by both
  EXPECT_NEAR(cube.texel(kPosZ, i, j)[0], 5.0f, 0.01f);
  EXPECT_LT(clip_cube.texel(kPosZ, i, j)[0], 0.01f);
  // The centre of +X only its own clipped shot sees: clipped it stays.
  EXPECT_FLOAT_EQ(cube.texel(kPosX, n / 2, n / 2)[0], 1.0f);
  EXPECT_FLOAT_EQ(clip_cube.texel(kPosX, n / 2, n / 2)[0], 1.0f);
}

// Two shots blended with a known gain: the +X shot exposed 1.3× and white-balanced warmer than
// the rest (×1.3, ×1.1, ×0.8 in R, G, B). Its gain is recovered within 1 % per channel, the
// others keep theirs (the median shot's exposure is kept), and the cube comes back.
TEST(ShotGains, AShotsExposureAndWhiteBalanceAreMatchedToItsNeighbours) {
  const Image world = feature_world(3);
  std::array<Mat3d, 6> aligned;
  aligned.fill(Mat3d::Identity());
  ShotSet set = handheld_shots(world, aligned, 110, 320, 240);
  const Rgb off(1.3f, 1.1f, 0.8f);
  for (int y = 0; y < set.shots[kPosX].height; ++y)
    for (int x = 0; x < set.shots[kPosX].width; ++x) set.shots[kPosX].set_rgb(x, y, set.shots[kPosX].rgb(x, y) * off);
  const ShotGains g = overlap_gains(set);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(g.gain[kPosX][c] * off[c], 1.0f, 0.01f) << "channel " << c;
  for (int s : {kNegX, kPosY, kNegY, kPosZ, kNegZ})
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(g.gain[std::size_t(s)][c], 1.0f, 0.01f) << face_name(s) << " " << c;
  EXPECT_EQ(g.pairs[kPosX], 4);  // its four neighbours; the opposite shot does not overlap
  // Against the cube the shots give without the change: the change is undone.
  const int n = 64;
  const CubeMap clean = assemble_cube(handheld_shots(world, aligned, 110, 320, 240), n);
  const double before = mean_relative_error(assemble_cube(set, n), clean);
  apply_gains(set, g);
  EXPECT_LT(mean_relative_error(assemble_cube(set, n), clean), 0.05 * before);
}

// A plain room lit from above: radiance e^(3 sin(elevation)), no features. Six shots exposed alike,
// +X pitched up 3° by the hand and kept at its nominal aim (nothing to register it by). Its
// overlaps compare rays 3° apart along a gradient of 3 per radian, so every pair says it is
// brighter than it is (by up to e^(3 · 3°) = 1.17 near the horizon): taken as an exposure, its gain
// comes out 0.90.
// aimed_pairs leaves its pairs out (it keeps 1), and still matches a shot whose aim is known (−Z
// exposed 1.25×: the median's and the registered group's).
TEST(ShotGains, AShotAtItsNominalAimIsNotComparedWithItsNeighbours) {
  Image world(512, 256, 3);
  for (int y = 0; y < world.height; ++y) {
    const double elevation = kPi * (0.5 - (y + 0.5) / world.height);
    for (int x = 0; x < world.width; ++x) world.set_rgb(x, y, Rgb::Constant(float(std::exp(3 * std::sin(elevation)))));
  }
  std::array<Mat3d, 6> aims;
  aims.fill(Mat3d::Identity());
  aims[kPosX] = test::rotation(deg_to_rad(3.0) * shot_basis(kPosX, kNegZ).right);
  ShotSet set = test::handheld_shots(world, aims, 110, 160, 120);
  for (int y = 0; y < set.shots[kNegZ].height; ++y)
    for (int x = 0; x < set.shots[kNegZ].width; ++x) set.shots[kNegZ].set_rgb(x, y, set.shots[kNegZ].rgb(x, y) * 1.25f);
  // Compared with every neighbour, +X's misaim is taken for its exposure.
  const ShotGains all = overlap_gains(set);
  EXPECT_LT(all.gain[kPosX][1], 0.95f);
  // Registered together, the other five; +X not registered.
  Registration r;
  for (int s = 0; s < 6; ++s) r.shots[std::size_t(s)].registered = s != kPosX, r.group[std::size_t(s)] = s == kPosX;
  const ShotPairs pairs = aimed_pairs(r, nullptr, nullptr);
  for (int s = 0; s < 6; ++s) EXPECT_FALSE(pairs[kPosX][std::size_t(s)]) << face_name(s);
  EXPECT_TRUE(pairs[kNegZ][kPosY]);
  const ShotGains aimed = overlap_gains(set, nullptr, pairs);
  EXPECT_EQ(aimed.pairs[kPosX], 0);
  EXPECT_EQ(aimed.gain[kPosX][1], 1.0f);
  EXPECT_NEAR(aimed.gain[kNegZ][1] * 1.25f, 1.0f, 0.01f);
  for (int s : {kNegX, kPosY, kNegY, kPosZ}) EXPECT_NEAR(aimed.gain[std::size_t(s)][1], 1.0f, 0.01f) << face_name(s);
  // Aimed absolutely: by the room box's lines (not where they only levelled it), or by the photo.
  LineAnchor lines;
  lines.anchored[kPosX] = lines.anchored[kPosZ] = true;
  EXPECT_TRUE(aimed_pairs(r, &lines, nullptr)[kPosX][kPosZ]);
  lines.axes = LineAxes::vertical;
  EXPECT_FALSE(aimed_pairs(r, &lines, nullptr)[kPosX][kPosZ]);
  PhotoAnchor photo;
  photo.anchored[kPosX] = photo.anchored[kNegZ] = true;
  EXPECT_TRUE(aimed_pairs(r, nullptr, &photo)[kPosX][kNegZ]);
}

// The matches' verification: 40 rays turned by a known rotation among 400 random pairs (noise,
// repeated texture). RANSAC with the rotation model keeps the 40 and only them, and the rotation
// refitted on them is the true one.
TEST(ShotRegistration, RotationRansacFindsTheTurnedRaysAmongNoise) {
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> spread(-0.3, 0.3);
  const Mat3d R = Eigen::AngleAxisd(deg_to_rad(3.0), Vec3d(0.3, 1, 0.2).normalized()).toRotationMatrix();
  std::vector<RayPair> pairs;
  for (int k = 0; k < 40; ++k) {
    const Vec3d u = Vec3d(spread(rng), spread(rng), 1).normalized();
    pairs.push_back({u, R * u});
  }
  for (int k = 0; k < 400; ++k)
    pairs.push_back({Vec3d(spread(rng), spread(rng), 1).normalized(), Vec3d(spread(rng), spread(rng), 1).normalized()});
  std::shuffle(pairs.begin(), pairs.end(), rng);
  const std::vector<RayPair> in = rotation_inliers(pairs, deg_to_rad(0.05));
  ASSERT_EQ(in.size(), 40u);
  for (const RayPair& p : in) EXPECT_LT((R * p.u_a - p.u_b).norm(), 1e-9);
  EXPECT_LT(angle_deg(kabsch_rotation(in), R), 1e-6);
}

// Through the scene file: "register" defaults to "auto", whose aims the environment reports (a
// plain shot named in warnings, with what that leaves unmatched); "none" keeps the nominal aims; anything else, or
// "register" beside an HDR image, is an error at its place.
TEST(ShotRegistration, TheSceneFileTurnsItOnAndOff) {
  test::TempDir dir;
  ShotSet set = handheld_shots(feature_world(7), misaims(11), 110, 800, 600);
  set.shots[kPosY] = Image(800, 600, 3, 0.7f);
  const char* keys[6] = {"+x", "-x", "up", "down", "+z", "-z"};
  nlohmann::json shots = {{"hfov_deg", 110}, {"faced", "-z"}};
  // The cube's size is not this test's concern: 128 rather than the shots' natural 560 (under the
  // sanitizers, building and sampling that cube was most of this test's 40 s).
  for (int s = 0; s < 6; ++s) {
    write_image(dir.file(std::string("shot") + std::to_string(s) + ".exr"), set.shots[std::size_t(s)]);
    shots[keys[s]] = std::string("shot") + std::to_string(s) + ".exr";
  }
  write_image(dir.file("photo.png"), Image(8, 8, 3, 0.5f));
  nlohmann::json scene = {{"photo", "photo.png"},
                          {"camera", {{"eye", {0, 1, 0}}, {"look", {0, 1, -1}}, {"hfov_deg", 60}}},
                          {"environment", {{"shots", shots}, {"face_size", 256}}}};
  Warnings w;
  EnvironmentInfo info;
  load_environment(parse_scene_file(dir.write("auto.json", scene.dump())).environment, w, &info);
  ASSERT_TRUE(info.registration);
  EXPECT_TRUE(info.registration->shots[kPosX].registered);
  EXPECT_FALSE(info.registration->shots[kPosY].registered);
  // The plain shot is named twice: it matched no neighbour, and it holds no vertical edge to level
  // it by (room_lines.h: without a room box the plumb lines level each group).
  ASSERT_EQ(w.items.size(), 2u) << w.items.back();
  EXPECT_NE(w.items[0].find("shots up: too few vertical lines to level them"), std::string::npos) << w.items[0];
  EXPECT_EQ(w.items[1].rfind(dir.file("shot2.exr") + ": not registered: no features", 0), 0u) << w.items[1];
  // Left at its nominal aim, it is compared with no neighbour (shot_gains.h), and the message says
  // so: its exposure stays as shot.
  EXPECT_NE(w.items[1].find("its nominal direction is used, and its exposure and white balance are not matched"),
            std::string::npos)
      << w.items[1];
  ASSERT_TRUE(info.line_anchor);
  EXPECT_TRUE(info.line_anchor->anchored[kPosX]);

  scene["environment"]["register"] = "none";
  Warnings w2;
  EnvironmentInfo info2;
  load_environment(parse_scene_file(dir.write("none.json", scene.dump())).environment, w2, &info2);
  EXPECT_FALSE(info2.registration);
  EXPECT_TRUE(w2.items.empty());

  scene["environment"]["register"] = "always";
  EXPECT_THROW(parse_scene_file(dir.write("bad.json", scene.dump())), InputError);
  scene["environment"] = {{"image", "photo.png"}, {"register", "auto"}};
  try {
    parse_scene_file(dir.write("image.json", scene.dump()));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("register"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace insitu
