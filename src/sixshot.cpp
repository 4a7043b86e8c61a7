#include "sixshot.h"

#include <algorithm>
#include <cassert>
#include <fmt/format.h>

#include "error.h"

namespace insitu {

namespace {
Vec3d face_axis(int face) {
  static const Vec3d axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  return axes[face];
}
}  // namespace

ShotBasis shot_basis(int face, int faced_face) {
  assert(faced_face == kPosX || faced_face == kNegX || faced_face == kPosZ || faced_face == kNegZ);
  ShotBasis b;
  b.forward = face_axis(face);
  if (face == kPosY) b.up = -face_axis(faced_face);
  else if (face == kNegY) b.up = face_axis(faced_face);
  else b.up = Vec3d(0, 1, 0);
  b.right = b.forward.cross(b.up);
  return b;
}

int natural_face_size(const ShotSet& set, int max_face_size) {
  const double scale = 1.0 / std::tan(0.5 * deg_to_rad(set.hfov_deg));  // tan 45° / tan(hfov/2)
  int n = max_face_size;
  for (const Image& shot : set.shots)
    n = std::min(n, std::max(1, int(std::lround(std::min(shot.width, shot.height) * scale))));
  return n;
}

CubeMap assemble_cube(const ShotSet& set, int n) {
  CubeMap cube(n);
  const double tan_half = std::tan(0.5 * deg_to_rad(set.hfov_deg));
  for (int f = 0; f < 6; ++f) {
    Image shot = set.shots[f];
    if (shot.width != shot.height)
      throw InputError(set.names[f], fmt::format("shot is {}x{}, not square (non-square shots are "
                                                 "not supported yet)", shot.width, shot.height));
    // Shrink a shot larger than its face by area averaging (which keeps its integral) before
    // sampling it. The 1e-9 keeps tan 45° = 0.99999999999999989 from rounding n up.
    const int needed = std::max(1, int(std::ceil(n * tan_half - 1e-9)));
    if (shot.width > needed) shot = resize(shot, needed, needed, "box");
    const ShotBasis b = shot_basis(f, set.faced_face);
    const double w = shot.width, f_px = 0.5 * w / tan_half;
    long uncovered = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vec3d d = texel_direction(f, i, j, n).cast<double>();
        const double z = d.dot(b.forward);
        // Pixel position (corner origin) of the direction in the shot.
        const double px = 0.5 * w + f_px * d.dot(b.right) / z;
        const double py = 0.5 * w - f_px * d.dot(b.up) / z;
        const double tol = 1e-3;
        if (px < -tol || px > w + tol || py < -tol || py > w + tol) ++uncovered;
        const double x = std::clamp(px - 0.5, 0.0, w - 1.0), y = std::clamp(py - 0.5, 0.0, w - 1.0);
        const int x0 = std::min(int(x), shot.width - 1), y0 = std::min(int(y), shot.height - 1);
        const int x1 = std::min(x0 + 1, shot.width - 1), y1 = std::min(y0 + 1, shot.height - 1);
        const float wx = float(x - x0), wy = float(y - y0);
        const Rgb c = (1 - wy) * ((1 - wx) * shot.rgb(x0, y0) + wx * shot.rgb(x1, y0)) +
                      wy * ((1 - wx) * shot.rgb(x0, y1) + wx * shot.rgb(x1, y1));
        cube.set_texel(f, i, j, c);
      }
    if (uncovered > 0)
      throw InputError(set.names[f],
                       fmt::format("shot covers only {:.1f}% of face {} (field of view {}° is "
                                   "below 90°)", 100.0 * (1.0 - double(uncovered) / (double(n) * n)),
                                   face_name(f), set.hfov_deg));
  }
  cube.update_borders();
  return cube;
}

}  // namespace insitu
