#include "relight/photo_fill.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include "light/sixshot.h"

namespace insitu {

namespace {

constexpr int kMaxFootprintPoints = 4;  // per side of a texel
constexpr int kLevelPixels = 4000;      // photo pixels on a grid, at most, for the level

// Where the room's wall along `dir` from `origin` is: its point, unless the ray leaves through an
// opening (or not at all).
std::optional<Vec3f> wall_point(const RoomLight& room, const Vec3f& origin, const Vec3f& dir) {
  float t = 0;
  int axis = 0;
  if (!room.exit(origin, dir, &t, &axis)) return std::nullopt;
  const Vec3f q = origin + t * dir;
  if (room.openings_at(q, axis) > 0) return std::nullopt;
  return q;
}

// The photo pixels that show the room's walls unclipped: not clipped in any channel, finite, and
// on a wall (a pixel through an opening shows the outside from elsewhere, and one beside it would
// bleed into a texel's bilinear sample).
std::vector<std::uint8_t> usable_pixels(const RoomLight& room, const Camera& camera, const Image& photo,
                                        const Image& photo_clipped) {
  std::vector<std::uint8_t> usable(std::size_t(photo.width) * std::size_t(photo.height));
  tbb::parallel_for(0, photo.height, [&](int y) {
    for (int x = 0; x < photo.width; ++x) {
      const Ray ray = camera.ray(Vec2d(x + 0.5, y + 0.5));
      usable[std::size_t(y) * std::size_t(photo.width) + std::size_t(x)] =
          photo_clipped.rgb(x, y).maxCoeff() <= 0 && photo.rgb(x, y).allFinite() &&
          wall_point(room, ray.origin, ray.dir).has_value();
    }
  });
  return usable;
}

// The photo's radiance at a world point: bilinear between the four pixels around its projection,
// all of them usable, the point in front of the camera and inside the frame.
std::optional<Rgb> photo_at(const Camera& camera, const Image& photo, const std::vector<std::uint8_t>& usable,
                            const Vec3f& q) {
  double depth = 0;
  const Vec2d uv = camera.project(q.cast<double>(), &depth);
  const double x = uv.x() - 0.5, y = uv.y() - 0.5;
  if (!(depth > 0) || !(x >= 0) || !(y >= 0) || x > photo.width - 1 || y > photo.height - 1) return std::nullopt;
  const int x0 = std::min(int(x), photo.width - 1), y0 = std::min(int(y), photo.height - 1);
  const int x1 = std::min(x0 + 1, photo.width - 1), y1 = std::min(y0 + 1, photo.height - 1);
  for (const auto& [px, py] : {std::pair{x0, y0}, {x1, y0}, {x0, y1}, {x1, y1}})
    if (!usable[std::size_t(py) * std::size_t(photo.width) + std::size_t(px)]) return std::nullopt;
  return bilinear_rgb(photo, x, y);
}

// The offsets log Y(light) − log Y(photo), whose median is the level, over a grid of photo
// pixels whose wall point a shot covered, unclipped in both.
std::vector<double> level_offsets(const CubeMap& radiance, const std::vector<bool>& covered, const CubeMap* clipped,
                                  const RoomLight& room, const RoomBox& box, const Camera& camera, const Image& photo,
                                  const std::vector<std::uint8_t>& usable) {
  const int n = radiance.size();
  const int stride = std::max(1, int(std::ceil(std::sqrt(double(photo.width) * photo.height / kLevelPixels))));
  std::vector<double> offsets;
  for (int y = stride / 2; y < photo.height; y += stride)
    for (int x = stride / 2; x < photo.width; x += stride) {
      const Rgb p = photo.rgb(x, y);
      if (!usable[std::size_t(y) * std::size_t(photo.width) + std::size_t(x)] || !(luminance(p) > 1e-6f)) continue;
      const Ray ray = camera.ray(Vec2d(x + 0.5, y + 0.5));
      const auto q = wall_point(room, ray.origin, ray.dir);
      if (!q) continue;
      const Vec3f dir = *q - box.capture;
      const FaceCoord fc = direction_to_face(dir);
      const int i = nearest_texel_index(fc.s, n), j = nearest_texel_index(fc.t, n);
      if (!covered[texel_index(fc.face, i, j, n)]) continue;
      if (clipped && clipped->lookup_nearest(dir).maxCoeff() > 0) continue;
      const float l = luminance(radiance.texel(fc.face, i, j));
      if (!(l > 1e-6f) || !std::isfinite(l)) continue;
      offsets.push_back(std::log(double(l) / luminance(p)));
    }
  return offsets;
}

// The number of points per side of a texel's footprint: one per two photo pixels (a bilinear
// sample spans two), from 1 to kMaxFootprintPoints; 0 where the texel's centre is not seen. The
// footprint's side in pixels is twice the larger offset between the projections of its centre
// and of its corner.
int footprint_points(int face, int i, int j, int n, const RoomLight& room, const RoomBox& box, const Camera& camera) {
  const auto centre = wall_point(room, box.capture, texel_direction(face, i, j, n));
  const auto corner =
      wall_point(room, box.capture, face_to_direction(face, float(i) / float(n), float(j) / float(n)).normalized());
  if (!centre || !corner) return 0;
  double depth_centre = 0, depth_corner = 0;
  const Vec2d uv_centre = camera.project(centre->cast<double>(), &depth_centre);
  const Vec2d uv_corner = camera.project(corner->cast<double>(), &depth_corner);
  if (!(depth_centre > 0) || !(depth_corner > 0)) return 0;
  const double side_px = 2 * (uv_centre - uv_corner).cwiseAbs().maxCoeff();
  return std::clamp(int(std::ceil(side_px / 2)), 1, kMaxFootprintPoints);
}

// The photo's mean over an uncovered texel's footprint (footprint_points² points), if it sees all
// of them on a wall.
std::optional<Rgb> texel_from_photo(int face, int i, int j, int n, const RoomLight& room, const RoomBox& box,
                                    const Camera& camera, const Image& photo, const std::vector<std::uint8_t>& usable) {
  const int k = footprint_points(face, i, j, n, room, box, camera);
  if (k == 0) return std::nullopt;
  Rgb sum = Rgb::Zero();
  for (int b = 0; b < k; ++b)
    for (int a = 0; a < k; ++a) {
      const float s = (float(i) + (float(a) + 0.5f) / float(k)) / float(n);
      const float t = (float(j) + (float(b) + 0.5f) / float(k)) / float(n);
      const auto q = wall_point(room, box.capture, face_to_direction(face, s, t).normalized());
      if (!q) return std::nullopt;
      const auto p = photo_at(camera, photo, usable, *q);
      if (!p) return std::nullopt;
      sum += *p;
    }
  return Rgb(sum / float(k * k));
}

}  // namespace

PhotoFill fill_from_photo(CubeMap& radiance, const std::vector<bool>& covered, const CubeMap* clipped,
                          const RoomBox& box, const Camera& camera, const Image& photo_linear,
                          const Image& photo_clipped) {
  PhotoFill out;
  const int n = radiance.size();
  if (covered.size() != std::size_t(6) * std::size_t(n) * std::size_t(n)) return out;
  out.uncovered = long(std::count(covered.begin(), covered.end(), false));
  const RoomLight room(CubeMap(1), box);
  if (!room.inside(camera.eye_world().cast<float>())) {
    out.reason = "the photo's camera is outside the room box";
    return out;
  }
  const std::vector<std::uint8_t> usable = usable_pixels(room, camera, photo_linear, photo_clipped);
  std::vector<double> offsets = level_offsets(radiance, covered, clipped, room, box, camera, photo_linear, usable);
  out.level_pixels = int(offsets.size());
  if (out.level_pixels < kPhotoFillMinPixels) {
    out.reason = fmt::format("{} photo pixels see walls the shots covered ({} needed to match the photo's level)",
                             out.level_pixels, kPhotoFillMinPixels);
    return out;
  }
  std::nth_element(offsets.begin(), offsets.begin() + std::ptrdiff_t(offsets.size() / 2), offsets.end());
  out.level = std::exp(offsets[offsets.size() / 2]);
  // Each face row in parallel: the photo's texels, and the weight that fill_uncovered keeps.
  CubeMap weight(n);
  std::vector<long> row_count(std::size_t(6) * std::size_t(n), 0);
  tbb::parallel_for(0, 6 * n, [&](int row) {
    const int f = row / n, j = row % n;
    for (int i = 0; i < n; ++i) {
      if (covered[texel_index(f, i, j, n)]) {
        weight.set_texel(f, i, j, Rgb::Ones());
        continue;
      }
      const auto p = texel_from_photo(f, i, j, n, room, box, camera, photo_linear, usable);
      if (!p) continue;
      radiance.set_texel(f, i, j, float(out.level) * *p);
      weight.set_texel(f, i, j, Rgb::Ones());
      ++row_count[std::size_t(row)];
    }
  });
  for (long c : row_count) out.from_photo += c;
  if (out.from_photo == 0) {
    out.reason = "the photo sees none of the uncovered directions on the room's walls";
    return out;
  }
  radiance.update_borders();
  weight.update_borders();
  fill_uncovered(radiance, weight);
  return out;
}

}  // namespace insitu
