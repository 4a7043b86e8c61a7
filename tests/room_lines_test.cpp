// The room's lines as the anchor of the shots' aims (light/room_lines.h): misaimed main-camera
// shots of a synthetic Manhattan room, which overlap nothing, are turned back to its axes.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>

#include "core/image.h"
#include "handheld_shots.h"
#include "light/environment.h"
#include "light/room_lines.h"
#include "light/sixshot.h"
#include "scene/scene_file.h"
#include "test_util.h"

namespace insitu {
namespace {

// A box room seen from inside: each wall its own grey, panelled by dark lines every 0.4 m along
// both of its axes (the box's edges among them), 1 cm wide.
struct PanelledRoom {
  Vec3d lo{-2.0, 0.0, -2.5}, hi{2.0, 2.6, 2.5}, eye{0.3, 1.2, 0.2};
  Rgb operator()(const Vec3f& d_f) const {
    const Vec3d d = d_f.cast<double>();
    double t = 1e30;
    int axis = 0;
    for (int a = 0; a < 3; ++a) {
      if (d[a] == 0) continue;
      const double ta = ((d[a] > 0 ? hi[a] : lo[a]) - eye[a]) / d[a];
      if (ta < t) t = ta, axis = a;
    }
    const Vec3d q = eye + t * d;
    const float grey = 0.3f + 0.1f * float(axis) + (d[axis] > 0 ? 0.15f : 0.0f);
    for (int a = 0; a < 3; ++a) {
      if (a == axis) continue;
      const double u = q[a] / 0.4;
      if (std::abs(u - std::round(u)) * 0.4 < 0.005) return Rgb::Constant(0.03f);
    }
    return Rgb::Constant(grey);
  }
};

// The shot as a camera takes it: each pixel the mean of k×k samples over its area. Point samples
// would alias the 1 cm lines into stairs, whose segments LSD finds tilted by a pixel per step; no
// lens and sensor do that.
template <typename World>
Image camera_shot(const World& room, const ShotBasis& b, double hfov_deg, int w, int h, int k) {
  const Image fine = render_shot(room, b, hfov_deg, w * k, h * k);
  Image shot(w, h, 3, 0.0f);
  for (int y = 0; y < h * k; ++y)
    for (int x = 0; x < w * k; ++x) shot.set_rgb(x / k, y / k, shot.rgb(x / k, y / k) + fine.rgb(x, y) / float(k * k));
  return shot;
}

// Six 70° shots of `world` (a main camera: no two overlap), each turned by its true aim: 640 × 480
// as a camera takes them where `fine(s)`, else 320 × 240 point samples (a shot the test only needs
// to be there).
template <typename World, typename Fine>
ShotSet main_camera_shots(const World& world, const std::array<Mat3d, 6>& truth, Fine fine) {
  ShotSet set;
  set.faced_face = kNegZ;
  set.set_hfov(70);
  for (int s = 0; s < 6; ++s) {
    const ShotBasis b = shot_basis(s, kNegZ);
    const Mat3d& R = truth[std::size_t(s)];
    const ShotBasis aimed{R * b.forward, R * b.up, R * b.right};
    set.shots[std::size_t(s)] =
        fine(s) ? camera_shot(world, aimed, 70, 640, 480, 3) : render_shot(world, aimed, 70, 320, 240);
    set.names[std::size_t(s)] = face_name(s);
  }
  return set;
}

// 70° shots (a main camera: no two overlap), misaimed by σ = 2° per axis: each is anchored on its
// own and the misaim falls to a tenth on average. Each comes back within 0.5°, a quarter of the
// issue's 2° goal: over eight seeds the worst was 0.17°, since a 640-pixel shot's hundred segments
// each hold an axis to a fraction of a pixel (0.13° per pixel at this focal length).
TEST(RoomLines, MisaimedShotsOfAManhattanRoomAreTurnedToItsAxes) {
  const PanelledRoom room;
  const std::array<Mat3d, 6> truth = test::misaims(21);
  const ShotSet set = main_camera_shots(room, truth, [](int) { return true; });
  const LineAnchor a = anchor_to_room_axes(set, {0, 1, 2, 3, 4, 5});
  double sum_before = 0, sum_after = 0;
  for (int s = 0; s < 6; ++s) {
    EXPECT_TRUE(a.anchored[std::size_t(s)]) << face_name(s) << ": " << a.reason[std::size_t(s)];
    const double before = test::angle_deg(Mat3d::Identity(), truth[std::size_t(s)]);
    const double after = test::angle_deg(a.correction[std::size_t(s)], truth[std::size_t(s)]);
    EXPECT_LT(after, 0.5) << face_name(s) << ": misaimed " << before << "°";
    sum_before += before, sum_after += after;
    int families = 0;
    for (int n : a.lines[std::size_t(s)]) families += n >= 10;
    EXPECT_GE(families, 2) << face_name(s);
  }
  EXPECT_LT(sum_after, 0.1 * sum_before);
}

// Main-camera shots of the panelled room turned 20° about the vertical, aimed by `truth`; the
// ceiling and floor point-sampled.
ShotSet turned_room_shots(const std::array<Mat3d, 6>& truth) {
  const PanelledRoom room;
  const Mat3d turn = test::rotation(Vec3d(0, deg_to_rad(20.0), 0));
  const auto turned_room = [&](const Vec3f& d) { return room((turn.transpose() * d.cast<double>()).cast<float>()); };
  return main_camera_shots(turned_room, truth, [](int s) { return s != kPosY && s != kNegY; });
}

// The same room turned 20° about the vertical, as a room is when nothing says where its walls run
// (no room box), or when a box is drawn askew: taken as the axes, its walls' lines would turn the
// shots by 20°, a yaw no hand makes, and LineAxes::room refuses it (off_box, the turn it would
// have made, and the reason); but its vertical edges are still plumb. With LineAxes::vertical each side shot is
// levelled: its tilt (where it takes the world's up) comes back within 0.3° and falls to a tenth on average, while its
// yaw, which plumb lines cannot see, is left as it was (ω_y = 0). The 70° ceiling and floor shots see no vertical edge,
// and say so.
TEST(RoomLines, PlumbEdgesLevelShotsOfARoomTurnedOffTheAxes) {
  const std::array<Mat3d, 6> truth = test::misaims(5);
  const ShotSet set = turned_room_shots(truth);
  const std::array<int, 6> alone = {0, 1, 2, 3, 4, 5};
  const LineAnchor room_axes = anchor_to_room_axes(set, alone, LineAxes::room);
  const LineAnchor plumb = anchor_to_room_axes(set, alone, LineAxes::vertical);
  // Where a shot takes the world's up: the error turn E = G R⁻¹ moves the true up by its tilt.
  const auto tilt_deg = [](const Mat3d& E) { return rad_to_deg(std::acos(std::min(1.0, E(1, 1)))); };
  double sum_before = 0, sum_after = 0;
  int off_box = 0;
  for (int s = 0; s < 6; ++s) {
    const auto i = std::size_t(s);
    if (s == kPosY || s == kNegY) {
      EXPECT_FALSE(plumb.anchored[i]) << face_name(s);
      EXPECT_NE(plumb.reason[i].find("too few vertical lines"), std::string::npos) << plumb.reason[i];
      continue;
    }
    // Taken as a room box's axes, the turned walls would turn the shot by about the walls' 20°:
    // not applied, and said why. Off the box by more than a hand misaims, the shot is levelled by
    // its plumb lines instead, exactly as LineAxes::vertical levels it; or (where the turned walls'
    // lines fall outside the gates) too few lines along the box's axes, and it is not turned.
    if (room_axes.off_box[i]) {
      ++off_box;
      EXPECT_GT(room_axes.off_box_turn_deg[i], kMaxHandTurnDeg) << face_name(s);
      EXPECT_NE(room_axes.reason[i].find("off the room box's axes"), std::string::npos) << room_axes.reason[i];
      EXPECT_EQ(room_axes.anchored[i], plumb.anchored[i]) << face_name(s);
      EXPECT_TRUE(room_axes.correction[i].isApprox(plumb.correction[i], 1e-12)) << face_name(s);
      EXPECT_EQ(room_axes.lines[i], plumb.lines[i]) << face_name(s);
    } else {
      EXPECT_FALSE(room_axes.anchored[i]) << face_name(s);
      EXPECT_TRUE(room_axes.correction[i].isIdentity()) << face_name(s);
      EXPECT_NE(room_axes.reason[i].find("too few straight lines"), std::string::npos) << room_axes.reason[i];
    }
    ASSERT_TRUE(plumb.anchored[i]) << face_name(s) << ": " << plumb.reason[i];
    const double before = tilt_deg(truth[i].transpose()), after = tilt_deg(plumb.correction[i] * truth[i].transpose());
    EXPECT_LT(after, 0.3) << face_name(s) << ": tilted " << before << "°";
    sum_before += before, sum_after += after;
    const Eigen::AngleAxisd g(plumb.correction[i]);
    EXPECT_LT(std::abs(g.axis().y() * g.angle()), 1e-12) << face_name(s) << ": the yaw is not the lines'";
    EXPECT_GE(plumb.lines[i][1], 10) << face_name(s);
  }
  EXPECT_LT(sum_after, 0.1 * sum_before);
  EXPECT_GE(off_box, 3);
}

// The same through the scene file: a room box drawn along the world's axes while the real walls
// run 20° off them. The shots are not turned by the box's 20°: the side shots it would have turned
// are levelled by their plumb lines as without a box, and one warning names them and asks whether
// the box is drawn along the walls.
TEST(RoomLines, ABoxDrawnOffTheWallsDoesNotTurnTheShots) {
  const std::array<Mat3d, 6> truth = test::misaims(5);
  const ShotSet set = turned_room_shots(truth);
  test::TempDir dir;
  nlohmann::json shots = {{"hfov_deg", 70}, {"faced", "-z"}};
  for (int s = 0; s < 6; ++s) {
    const std::string name = std::string("shot") + std::to_string(s) + ".exr";
    write_image(dir.file(name), set.shots[std::size_t(s)]);
    shots[face_name(s)] = name;
  }
  const nlohmann::json box = {{"min", {-2.0, 0.0, -2.5}}, {"max", {2.0, 2.6, 2.5}}, {"capture", {0.3, 1.2, 0.2}}};
  const nlohmann::json scene = {
      {"photo", "shot0.exr"},
      {"camera", {{"eye", {0, 1, 0}}, {"look", {0, 1, -1}}, {"hfov_deg", 60}}},
      {"environment", {{"shots", shots}, {"face_size", 256}, {"exposure", 1.0}, {"room_box", box}}}};
  Warnings w;
  EnvironmentInfo info;
  load_environment(parse_scene_file(dir.write("scene.json", scene.dump())).environment, w, &info);
  ASSERT_TRUE(info.line_anchor && info.registration);
  int off_box = 0;
  for (int s : {kPosX, kNegX, kPosZ, kNegZ}) {
    const auto i = std::size_t(s);
    if (!info.line_anchor->off_box[i]) continue;
    ++off_box;
    ASSERT_TRUE(info.line_anchor->anchored[i]) << face_name(s) << ": " << info.line_anchor->reason[i];
    // Not turned by the box's 15–22°: the aim stays within a misaim of the truth (levelling itself
    // is PlumbEdgesLevelShotsOfARoomTurnedOffTheAxes's).
    EXPECT_LT(test::angle_deg(info.registration->aim[i], truth[i]), 8.0) << face_name(s);
  }
  EXPECT_GE(off_box, 2);
  const auto warned = std::find_if(w.items.begin(), w.items.end(), [](const std::string& m) {
    return m.find("off the room box's axes") != std::string::npos;
  });
  ASSERT_NE(warned, w.items.end());
  EXPECT_NE(warned->find("levelled by their plumb lines only"), std::string::npos) << *warned;
}

// A plain room has no lines to hold on to: nothing is turned, and each shot says why.
TEST(RoomLines, APlainRoomAnchorsNothing) {
  ShotSet set;
  set.set_hfov(70);
  for (int s = 0; s < 6; ++s) {
    set.shots[std::size_t(s)] = Image(320, 240, 3, 0.5f);
    set.names[std::size_t(s)] = face_name(s);
  }
  const LineAnchor a = anchor_to_room_axes(set, {0, 1, 2, 3, 4, 5});
  for (int s = 0; s < 6; ++s) {
    EXPECT_FALSE(a.anchored[std::size_t(s)]);
    EXPECT_EQ(a.correction[std::size_t(s)], Mat3d::Identity());
    EXPECT_NE(a.reason[std::size_t(s)].find("too few straight lines"), std::string::npos);
  }
}

}  // namespace
}  // namespace insitu
