// The uncovered directions taken from the photo (relight/photo_fill.h). The room's walls have a
// known radiance L(q) that varies along them (no harmonic fill can reproduce it); the cube and the
// photo are both made from L by a slower, independent route: the slab method by hand from the
// capture point, or from the camera's ray. The shots cover the middle of each face only.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "light/sixshot.h"
#include "relight/photo_fill.h"

namespace insitu {
namespace {

constexpr int kFace = 32;
const RoomBox kBox{Vec3f(-2, 0, -2.5f), Vec3f(2, 2.5f, 2.5f), Vec3f(0, 1, 0), {}, std::nullopt};

Rgb wall_radiance(const Vec3f& q) {
  const float v = 1 + 0.5f * std::sin(1.7f * q.x() + 0.9f * q.y()) * std::cos(1.3f * q.z());
  return Rgb(0.6f, 0.5f, 0.4f) * v;
}

Vec3f box_exit(const RoomBox& box, const Vec3f& o, const Vec3f& d) {
  float t = 1e30f;
  for (int a = 0; a < 3; ++a) {
    if (d[a] > 0) t = std::min(t, (box.max[a] - o[a]) / d[a]);
    if (d[a] < 0) t = std::min(t, (box.min[a] - o[a]) / d[a]);
  }
  return o + t * d;
}

Rgb true_texel(int f, int i, int j) {
  return wall_radiance(box_exit(kBox, kBox.capture, texel_direction(f, i, j, kFace)));
}

// The shots saw the middle of each face (|s − ½|, |t − ½| < 0.3: a 62° square shot).
std::vector<bool> middle_covered() {
  std::vector<bool> covered(std::size_t(6) * kFace * kFace);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < kFace; ++j)
      for (int i = 0; i < kFace; ++i)
        covered[std::size_t((f * kFace + j) * kFace + i)] =
            std::abs((i + 0.5) / kFace - 0.5) < 0.3 && std::abs((j + 0.5) / kFace - 0.5) < 0.3;
  return covered;
}

// The cube as the assembly leaves it: the true light where covered, the rest filled.
CubeMap assembled(const std::vector<bool>& covered) {
  CubeMap cube(kFace), weight(kFace);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < kFace; ++j)
      for (int i = 0; i < kFace; ++i)
        if (covered[std::size_t((f * kFace + j) * kFace + i)]) {
          cube.set_texel(f, i, j, true_texel(f, i, j));
          weight.set_texel(f, i, j, Rgb::Ones());
        }
  cube.update_borders();
  weight.update_borders();
  fill_uncovered(cube, weight);
  return cube;
}

const Camera kCamera = Camera::look_at(Vec3d(1, 1.4, 2), Vec3d(-0.5, 0.8, -2.5), Vec3d(0, 1, 0), 80, 160, 120);

// The photo at `exposure` times the light's unit; `bright_at` (if given) puts 1000 where it holds.
template <class Where>
Image photo_of_room(const RoomBox& box, double exposure, Where bright_at) {
  Image photo(kCamera.width, kCamera.height, 3);
  for (int y = 0; y < photo.height; ++y)
    for (int x = 0; x < photo.width; ++x) {
      const Ray r = kCamera.ray(Vec2d(x + 0.5, y + 0.5));
      const Vec3f q = box_exit(box, r.origin, r.dir);
      photo.set_rgb(x, y, bright_at(x, q) ? Rgb::Constant(1000) : Rgb(float(exposure) * wall_radiance(q)));
    }
  return photo;
}
Image photo_of_room(double exposure) {
  return photo_of_room(kBox, exposure, [](int, const Vec3f&) { return false; });
}

Image unclipped() { return Image(kCamera.width, kCamera.height, 3); }

// The uncovered texels whose footprint the photo surely sees: the centre's projection at least 3
// pixels inside the frame.
std::vector<std::array<int, 3>> seen_by_photo(const std::vector<bool>& covered) {
  std::vector<std::array<int, 3>> seen;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < kFace; ++j)
      for (int i = 0; i < kFace; ++i) {
        if (covered[std::size_t((f * kFace + j) * kFace + i)]) continue;
        double depth = 0;
        const Vec2d uv =
            kCamera.project(box_exit(kBox, kBox.capture, texel_direction(f, i, j, kFace)).cast<double>(), &depth);
        if (depth > 0 && uv.x() > 3 && uv.y() > 3 && uv.x() < kCamera.width - 3 && uv.y() < kCamera.height - 3)
          seen.push_back({f, i, j});
      }
  return seen;
}

double worst_relative_error(const CubeMap& cube, const std::vector<std::array<int, 3>>& texels) {
  double worst = 0;
  for (const auto& [f, i, j] : texels)
    worst = std::max(worst, double(std::abs(luminance(cube.texel(f, i, j)) / luminance(true_texel(f, i, j)) - 1)));
  return worst;
}

TEST(PhotoFill, TakesTheWallsThePhotoSeesAtTheShotsLevel) {
  const std::vector<bool> covered = middle_covered();
  CubeMap cube = assembled(covered);
  const auto seen = seen_by_photo(covered);
  ASSERT_GT(seen.size(), 100u);
  // The neighbours' fill misses the walls' variation: what the photo must put right.
  EXPECT_GT(worst_relative_error(cube, seen), 0.15);
  const PhotoFill fill = fill_from_photo(cube, covered, nullptr, kBox, kCamera, photo_of_room(2.0), unclipped());
  EXPECT_TRUE(fill.reason.empty()) << fill.reason;
  EXPECT_NEAR(fill.level, 0.5, 0.005);  // the photo at twice the light's unit
  EXPECT_GE(fill.from_photo, long(seen.size()));
  EXPECT_LT(fill.from_photo, fill.uncovered);
  // The footprint's mean against the centre's value: L varies by at most ~4 % across a texel.
  EXPECT_LT(worst_relative_error(cube, seen), 0.04);
}

TEST(PhotoFill, LeavesClippedPixelsAndOpeningsToTheNeighbours) {
  const std::vector<bool> covered = middle_covered();
  // Clipped: the photo's left quarter shows 1000, and says it clipped.
  CubeMap cube = assembled(covered);
  Image clipped = unclipped();
  for (int y = 0; y < clipped.height; ++y)
    for (int x = 0; x < clipped.width / 4; ++x) clipped.set_rgb(x, y, Rgb::Ones());
  const Image left = photo_of_room(kBox, 1.0, [](int x, const Vec3f&) { return x < kCamera.width / 4; });
  const PhotoFill a = fill_from_photo(cube, covered, nullptr, kBox, kCamera, left, clipped);
  EXPECT_GT(a.from_photo, 0);
  // Through an opening on the far wall the photo shows 1000 (another view of the outside).
  RoomBox box = kBox;
  box.openings.push_back({2, Vec3f(-1.88f, 0.3f, -2.5f), Vec3f(1.88f, 2.3f, -2.5f)});
  CubeMap cube2 = assembled(covered);
  const auto in_opening = [&](int, const Vec3f& q) {
    return std::abs(q.z() + 2.5f) < 1e-4f && std::abs(q.x()) <= 1.88f && q.y() >= 0.3f && q.y() <= 2.3f;
  };
  const PhotoFill b =
      fill_from_photo(cube2, covered, nullptr, box, kCamera, photo_of_room(box, 1.0, in_opening), unclipped());
  EXPECT_GT(b.from_photo, 0);
  // Every texel within a factor 1.5 of the truth, as the neighbours' fill is: none took
  // any of the 1000.
  for (const CubeMap* c : {&cube, &cube2})
    for (int f = 0; f < 6; ++f)
      for (int j = 0; j < kFace; ++j)
        for (int i = 0; i < kFace; ++i) {
          const float ratio = luminance(c->texel(f, i, j)) / luminance(true_texel(f, i, j));
          ASSERT_TRUE(ratio > 1 / 1.5f && ratio < 1.5f) << f << " " << i << " " << j << ": " << ratio;
        }
}

TEST(PhotoFill, WithoutTheShotsWallsInViewTheLevelIsUnknownAndNothingIsFilled) {
  // The shots saw only the floor's middle, which the photo does not see.
  std::vector<bool> covered(std::size_t(6) * kFace * kFace, false);
  for (int j = 12; j < 20; ++j)
    for (int i = 12; i < 20; ++i) covered[std::size_t((kNegY * kFace + j) * kFace + i)] = true;
  CubeMap cube = assembled(covered);
  const CubeMap before = cube;
  const PhotoFill fill = fill_from_photo(cube, covered, nullptr, kBox, kCamera, photo_of_room(1.0), unclipped());
  EXPECT_EQ(fill.from_photo, 0);
  EXPECT_NE(fill.reason.find("needed to match the photo's level"), std::string::npos) << fill.reason;
  EXPECT_TRUE(cube.same_texels(before));
  // A camera outside the box sees the walls from behind: nothing either.
  RoomBox small = kBox;
  small.max.z() = 1.5f;
  CubeMap cube2 = assembled(middle_covered());
  const PhotoFill out =
      fill_from_photo(cube2, middle_covered(), nullptr, small, kCamera, photo_of_room(1.0), unclipped());
  EXPECT_EQ(out.from_photo, 0);
  EXPECT_EQ(out.reason, "the photo's camera is outside the room box");
}

}  // namespace
}  // namespace insitu
