// The light white-balanced to the photo (relight/photo_white_balance.h). Each photo is made by a
// slower, independent route: the camera's ray met with the box by hand (slabs) and the true cube
// looked up from the capture point toward that point, or along the ray without a box; then
// multiplied by a known balance and exposure. The gain must undo the balance and not the exposure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/colour.h"
#include "light/texel_geometry.h"
#include "relight/photo_white_balance.h"

namespace insitu {
namespace {

constexpr int kWbFace = 48;

// Walls of different colours, each varying across the face: a room, not a grey world.
CubeMap coloured_room() {
  const Rgb colours[6] = {{0.6f, 0.5f, 0.4f},   {0.3f, 0.4f, 0.5f},   {0.9f, 0.9f, 0.85f},
                          {0.35f, 0.25f, 0.2f}, {0.5f, 0.55f, 0.45f}, {0.7f, 0.6f, 0.65f}};
  CubeMap cube(kWbFace);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < kWbFace; ++j)
      for (int i = 0; i < kWbFace; ++i)
        cube.set_texel(f, i, j, colours[f] * (0.6f + 0.8f * float(i + j) / float(2 * kWbFace)));
  cube.update_borders();
  return cube;
}

const RoomBox kWbBox{Vec3f(-2, 0, -2.5f), Vec3f(2.5f, 2.6f, 2), Vec3f(0.3f, 1.0f, -0.4f), {}, std::nullopt};

// Where a ray from inside the box leaves it (the slab method, by hand).
Vec3f box_exit(const Vec3f& o, const Vec3f& d) {
  float t = 1e30f;
  for (int a = 0; a < 3; ++a) {
    if (d[a] > 0) t = std::min(t, (kWbBox.max[a] - o[a]) / d[a]);
    if (d[a] < 0) t = std::min(t, (kWbBox.min[a] - o[a]) / d[a]);
  }
  return o + t * d;
}

const Camera kWbCamera = Camera::look_at(Vec3d(1.8, 1.5, 1.4), Vec3d(-1, 0.8, -1.5), Vec3d(0, 1, 0), 75, 96, 72);

Image wb_photo_of(const CubeMap& truth, bool with_box, const Rgb& balance, float exposure) {
  Image photo(kWbCamera.width, kWbCamera.height, 3);
  for (int y = 0; y < photo.height; ++y)
    for (int x = 0; x < photo.width; ++x) {
      const Ray r = kWbCamera.ray(Vec2d(x + 0.5, y + 0.5));
      const Vec3f d = with_box ? (box_exit(r.origin, r.dir) - kWbBox.capture).normalized() : r.dir;
      photo.set_rgb(x, y, truth.lookup(d).cwiseProduct(balance) * exposure);
    }
  return photo;
}

// Y(w) = 1, so the expected gain is the balance normalized by its luminance.
Rgb normalized(const Rgb& w) { return w / luminance(w); }

TEST(PhotoWhiteBalance, UndoesTheShotsBalanceInABoxRoomAndKeepsTheExposure) {
  const CubeMap truth = coloured_room();
  const Rgb balance(1.15f, 1.0f, 0.8f);
  const Image photo = wb_photo_of(truth, true, balance, 0.7f);
  const WhiteBalance wb =
      white_balance_to_photo(truth, nullptr, kWbBox, kWbCamera, photo, Image(photo.width, photo.height, 3, 0.0f));
  ASSERT_TRUE(wb.determined) << wb.reason;
  EXPECT_GT(wb.pixels, kWhiteBalanceMinPixels);
  const Rgb expected = normalized(balance);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(wb.gain[c], expected[c], 0.01f * expected[c]) << "channel " << c;
  EXPECT_NEAR(luminance(wb.gain), 1.0f, 1e-5f);
}

TEST(PhotoWhiteBalance, UndoesItByDirectionWithoutABox) {
  const CubeMap truth = coloured_room();
  const Rgb balance(0.9f, 1.0f, 1.2f);
  const Image photo = wb_photo_of(truth, false, balance, 2.0f);
  const WhiteBalance wb =
      white_balance_to_photo(truth, nullptr, std::nullopt, kWbCamera, photo, Image(photo.width, photo.height, 3, 0.0f));
  ASSERT_TRUE(wb.determined) << wb.reason;
  const Rgb expected = normalized(balance);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(wb.gain[c], expected[c], 0.01f * expected[c]) << "channel " << c;
}

// A third of the photo something the room's light does not show (a red sofa already there): the
// median holds within 2 %.
TEST(PhotoWhiteBalance, WhatIsNotTheRoomDoesNotMoveIt) {
  const CubeMap truth = coloured_room();
  const Rgb balance(1.1f, 1.0f, 0.9f);
  Image photo = wb_photo_of(truth, true, balance, 1.0f);
  for (int y = photo.height / 2; y < photo.height; ++y)
    for (int x = 0; x < photo.width * 2 / 3; ++x) photo.set_rgb(x, y, Rgb(0.6f, 0.05f, 0.04f));
  const WhiteBalance wb =
      white_balance_to_photo(truth, nullptr, kWbBox, kWbCamera, photo, Image(photo.width, photo.height, 3, 0.0f));
  ASSERT_TRUE(wb.determined) << wb.reason;
  const Rgb expected = normalized(balance);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(wb.gain[c], expected[c], 0.02f * expected[c]) << "channel " << c;
}

// A photo clipped everywhere, or light clipped everywhere, determines nothing and says why.
TEST(PhotoWhiteBalance, NothingComparableDeterminesNothing) {
  const CubeMap truth = coloured_room();
  const Image photo = wb_photo_of(truth, true, Rgb::Ones(), 1.0f);
  const WhiteBalance a =
      white_balance_to_photo(truth, nullptr, kWbBox, kWbCamera, photo, Image(photo.width, photo.height, 3, 1.0f));
  EXPECT_FALSE(a.determined);
  EXPECT_EQ(a.pixels, 0);
  EXPECT_NE(a.reason.find("needed"), std::string::npos);
  CubeMap all_clipped(kWbFace);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < kWbFace; ++j)
      for (int i = 0; i < kWbFace; ++i) all_clipped.set_texel(f, i, j, Rgb::Ones());
  all_clipped.update_borders();
  const WhiteBalance b =
      white_balance_to_photo(truth, &all_clipped, kWbBox, kWbCamera, photo, Image(photo.width, photo.height, 3, 0.0f));
  EXPECT_FALSE(b.determined);
  EXPECT_EQ(scaled(truth, a.gain).texel(kPosX, 3, 4)[0], truth.texel(kPosX, 3, 4)[0]);
}

}  // namespace
}  // namespace insitu
