// The shots' common rotation anchored to the photo (light/photo_anchor.h). Handheld shots of a
// distant world whose misaims share a 3° turn: registration recovers their aims relative to each
// other but keeps the shared turn (its prior takes the mean misaim as zero); the photo of the same
// world, from a calibrated camera with its principal point off centre, takes it out.
#include <gtest/gtest.h>

#include "core/camera.h"
#include "handheld_shots.h"
#include "light/photo_anchor.h"
#include "light/shot_registration.h"

namespace insitu {
namespace {

using test::angle_deg;

// The photo of a distant world: each pixel the world along its ray.
Image distant_photo_of(const Image& world, const Camera& camera) {
  Image photo(camera.width, camera.height, 3);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x)
      photo.set_rgb(x, y, equirect_lookup(world, camera.ray(Vec2d(x + 0.5, y + 0.5)).dir));
  return photo;
}

Camera photo_camera() {
  Camera c = Camera::look_at(Vec3d(0, 1.5, 0), Vec3d(-1, 1.2, -2), Vec3d(0, 1, 0), 60, 960, 720);
  c.cx += 40, c.cy -= 25;  // calibrated off centre
  return c;
}

struct Handheld {
  Image world = test::feature_world(7);
  Mat3d common = test::rotation(Vec3d(deg_to_rad(1.5), deg_to_rad(-2.2), deg_to_rad(1.2)));
  std::array<Mat3d, 6> truth;
  ShotSet set;
  Registration registration;
  Handheld() {
    const std::array<Mat3d, 6> relative = test::misaims(11);
    for (int s = 0; s < 6; ++s) truth[std::size_t(s)] = common * relative[std::size_t(s)];
    set = test::handheld_shots(world, truth, 110, 800, 600);
    registration = register_shots(set);
    set.aim = registration.aim;
  }
};

TEST(PhotoAnchor, TheShotsCommonTurnIsTakenOutByThePhoto) {
  const Handheld h;
  const Camera camera = photo_camera();
  const PhotoAnchor a = anchor_to_photo(h.set, h.registration.group, distant_photo_of(h.world, camera), camera);
  int anchored = 0;
  for (int s = 0; s < 6; ++s) {
    const double before = angle_deg(h.registration.aim[std::size_t(s)], h.truth[std::size_t(s)]);
    EXPECT_GT(before, 2.0) << face_name(s) << ": registration alone keeps the common turn";
    if (!a.anchored[std::size_t(s)]) continue;
    ++anchored;
    const Mat3d aim = a.correction[std::size_t(s)] * h.registration.aim[std::size_t(s)];
    EXPECT_LT(angle_deg(aim, h.truth[std::size_t(s)]), 0.3) << face_name(s) << ", before " << before << "°";
    EXPECT_LT(a.residual_deg[std::size_t(s)], 0.2) << face_name(s);
  }
  // The photo looks at −z and a little −x: the shots that see it, and their group, are anchored.
  EXPECT_GE(anchored, 1);
  EXPECT_TRUE(a.anchored[kNegZ]) << a.reason[kNegZ];
}

// A photo of something else anchors nothing, and says why; the aims stay as registered.
TEST(PhotoAnchor, APhotoOfSomethingElseAnchorsNothing) {
  const Handheld h;
  const Camera camera = photo_camera();
  const PhotoAnchor a =
      anchor_to_photo(h.set, h.registration.group, distant_photo_of(test::feature_world(99), camera), camera);
  for (int s = 0; s < 6; ++s) {
    EXPECT_FALSE(a.anchored[std::size_t(s)]) << face_name(s);
    EXPECT_TRUE(a.correction[std::size_t(s)].isIdentity()) << face_name(s);
    EXPECT_EQ(a.residual_deg[std::size_t(s)], 0.0) << face_name(s);
    EXPECT_NE(a.reason[std::size_t(s)].find("needed"), std::string::npos) << a.reason[std::size_t(s)];
  }
}

// The centred view puts each world direction where a centred pinhole of focal fx would: a
// direction's pixel in the view, mapped back through the calibrated camera, is where the photo
// shows it.
TEST(PhotoAnchor, TheCentredViewIsThePhotosPinhole) {
  const Camera camera = photo_camera();
  Image photo(camera.width, camera.height, 3);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) photo.set_rgb(x, y, Rgb(float(x), float(y), 1));
  const Image view = centred_pinhole_view(photo, camera);
  // View pixel (i, j) at ray ((i + 0.5 − W/2)/fx, (j + 0.5 − H/2)/fy·fy/fx, 1): in the photo at
  // u = i + 0.5 − W/2 + cx, v = (j + 0.5 − H/2)·fy/fx + cy; the stored ramp is the pixel's index.
  for (int j = 100; j < 600; j += 97)
    for (int i = 100; i < 800; i += 101) {
      const double u = i + 0.5 - 480 + camera.cx, v = (j + 0.5 - 360) * camera.fy / camera.fx + camera.cy;
      EXPECT_NEAR(view.rgb(i, j)[0], u - 0.5, 1e-3) << i << "," << j;
      EXPECT_NEAR(view.rgb(i, j)[1], v - 0.5, 1e-3) << i << "," << j;
    }
}

}  // namespace
}  // namespace insitu
