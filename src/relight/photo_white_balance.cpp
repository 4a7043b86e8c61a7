#include "relight/photo_white_balance.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/colour.h"
#include "relight/fit_resolution.h"

namespace insitu {

namespace {

constexpr int kCompareFace = 64;

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// Where the photo's ray meets the light: clipped there, or through an opening (the light outside,
// which the photo may see from another side of the window), or a direction of the cube.
struct LightAlong {
  Rgb radiance = Rgb::Zero();
  bool usable = false;
};

LightAlong light_along(const RoomLight& light, const CubeMap& clipped, const std::optional<RoomBox>& box,
                       const Ray& ray) {
  Vec3f dir_cube = ray.dir;
  if (box) {
    float t = 0;
    int axis = 0;
    if (!light.exit(ray.origin, ray.dir, &t, &axis)) return {};
    const Vec3f q = ray.origin + t * ray.dir;
    if (light.openings_at(q, axis) > 0) return {};
    dir_cube = (q - box->capture).normalized();
  }
  if (clipped.lookup_nearest(dir_cube).maxCoeff() > 0) return {};
  return {light.radiance(ray.origin, ray.dir), true};
}

// The chromatic offsets o_c of the photo's grid pixels (see the header).
std::array<std::vector<double>, 3> offsets(const RoomLight& light, const CubeMap& clipped,
                                           const std::optional<RoomBox>& box, const Camera& camera, const Image& photo,
                                           const Image& photo_clipped) {
  const int stride = std::max(1, int(std::ceil(std::sqrt(double(photo.width) * photo.height / kWhiteBalancePixels))));
  std::array<std::vector<double>, 3> o;
  for (int y = stride / 2; y < photo.height; y += stride)
    for (int x = stride / 2; x < photo.width; x += stride) {
      const Rgb p = photo.rgb(x, y);
      if (photo_clipped.rgb(x, y).maxCoeff() > 0 || !(p.minCoeff() > 1e-6f) || !p.allFinite()) continue;
      const LightAlong l = light_along(light, clipped, box, camera.ray(Vec2d(x + 0.5, y + 0.5)));
      if (!l.usable || !(l.radiance.minCoeff() > 1e-6f) || !l.radiance.allFinite()) continue;
      const double log_y = std::log(double(luminance(p)) / luminance(l.radiance));
      for (int c = 0; c < 3; ++c) o[std::size_t(c)].push_back(std::log(double(p[c]) / l.radiance[c]) - log_y);
    }
  return o;
}

}  // namespace

WhiteBalance white_balance_to_photo(const CubeMap& radiance, const CubeMap* clipped, const std::optional<RoomBox>& box,
                                    const Camera& camera, const Image& photo_linear, const Image& photo_clipped) {
  const CubeMap none(radiance.size());
  const FitCubes small = shrink_for_fit(radiance, clipped ? *clipped : none, kCompareFace);
  const RoomLight light(small.radiance, box);
  const auto o = offsets(light, small.clipped, box, camera, photo_linear, photo_clipped);
  WhiteBalance wb;
  wb.pixels = int(o[0].size());
  if (wb.pixels < kWhiteBalanceMinPixels) {
    wb.reason =
        fmt::format("{} photo pixels see the room unclipped and lit ({} needed)", wb.pixels, kWhiteBalanceMinPixels);
    return wb;
  }
  for (int c = 0; c < 3; ++c) {
    const double m = median(o[std::size_t(c)]);
    std::vector<double> dev;
    for (double v : o[std::size_t(c)]) dev.push_back(std::abs(v - m));
    wb.gain[c] = float(std::exp(m));
    wb.sigma[c] = float(1.2533 * 1.4826 * median(dev) / std::sqrt(double(wb.pixels)));
  }
  wb.gain /= luminance(wb.gain);
  wb.determined = true;
  return wb;
}

}  // namespace insitu
