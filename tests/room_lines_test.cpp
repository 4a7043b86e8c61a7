// The room's lines as the anchor of the shots' aims (light/room_lines.h): misaimed main-camera
// shots of a synthetic Manhattan room, which overlap nothing, are turned back to its axes.
#include <gtest/gtest.h>

#include <cmath>

#include "handheld_shots.h"
#include "light/room_lines.h"
#include "light/sixshot.h"

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
Image camera_shot(const PanelledRoom& room, const ShotBasis& b, double hfov_deg, int w, int h, int k) {
  const Image fine = render_shot(room, b, hfov_deg, w * k, h * k);
  Image shot(w, h, 3, 0.0f);
  for (int y = 0; y < h * k; ++y)
    for (int x = 0; x < w * k; ++x) shot.set_rgb(x / k, y / k, shot.rgb(x / k, y / k) + fine.rgb(x, y) / float(k * k));
  return shot;
}

// 70° shots (a main camera: no two overlap), misaimed by σ = 2° per axis: each is anchored on its
// own and the misaim falls to a tenth on average. Each comes back within 0.5°, a quarter of the
// issue's 2° goal: over eight seeds the worst was 0.17°, since a 640-pixel shot's hundred segments
// each hold an axis to a fraction of a pixel (0.13° per pixel at this focal length).
TEST(RoomLines, MisaimedShotsOfAManhattanRoomAreTurnedToItsAxes) {
  const PanelledRoom room;
  const std::array<Mat3d, 6> truth = test::misaims(21);
  ShotSet set;
  set.faced_face = kNegZ;
  set.set_hfov(70);
  for (int s = 0; s < 6; ++s) {
    const ShotBasis b = shot_basis(s, kNegZ);
    const Mat3d& R = truth[std::size_t(s)];
    set.shots[std::size_t(s)] = camera_shot(room, ShotBasis{R * b.forward, R * b.up, R * b.right}, 70, 640, 480, 3);
    set.names[std::size_t(s)] = face_name(s);
  }
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
