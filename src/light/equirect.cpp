#include "light/equirect.h"

#include "light/panorama.h"

#include <algorithm>
#include <cassert>

namespace insitu {

Vec2f direction_to_equirect(const Vec3f& d) {
  const float phi = std::atan2(-d.z(), d.x());
  float u = 0.5f - phi / (2.0f * kPiF);
  u -= std::floor(u);
  const float v = std::acos(std::clamp(d.y(), -1.0f, 1.0f)) / kPiF;
  return {u, v};
}

Vec3f equirect_to_direction(float u, float v) {
  const float phi = (0.5f - u) * 2.0f * kPiF, theta = v * kPiF;
  const float st = std::sin(theta);
  return {st * std::cos(phi), std::cos(theta), -st * std::sin(phi)};
}

Rgb equirect_lookup(const Image& img, const Vec3f& dir) {
  const Vec2f uv = direction_to_equirect(dir);
  const float x = uv.x() * float(img.width) - 0.5f, y = uv.y() * float(img.height) - 0.5f;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float wx = x - float(x0), wy = y - float(y0);
  auto wrap = [&](int xi) { return ((xi % img.width) + img.width) % img.width; };
  auto clampy = [&](int yi) { return std::clamp(yi, 0, img.height - 1); };
  const Rgb a = img.rgb(wrap(x0), clampy(y0)), b = img.rgb(wrap(x0 + 1), clampy(y0));
  const Rgb c = img.rgb(wrap(x0), clampy(y0 + 1)), d = img.rgb(wrap(x0 + 1), clampy(y0 + 1));
  return (1 - wy) * ((1 - wx) * a + wx * b) + wy * ((1 - wx) * c + wx * d);
}

CubeMap cube_from_equirect(const Image& img, int n, int ss) {
  return cube_from_panorama(img, whole_panorama(img.width, img.height), 0.0, n, nullptr, ss);
}

CubeMap cube_from_strip(const Image& strip) {
  assert(strip.height == 6 * strip.width);
  const int n = strip.width;
  CubeMap cube(n);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) cube.set_texel(f, i, j, strip.rgb(i, f * n + j));
  cube.update_borders();
  return cube;
}

Image cube_to_strip(const CubeMap& cube) {
  const int n = cube.size();
  Image strip(n, 6 * n, 3);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) strip.set_rgb(i, f * n + j, cube.texel(f, i, j));
  return strip;
}

}  // namespace insitu
