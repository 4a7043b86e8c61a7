#include "studio/overlay_lines.h"

#include <cmath>

namespace insitu {

std::vector<Segment3> box_edges(const Vec3d& lo, const Vec3d& hi) {
  std::vector<Segment3> edges;
  const auto corner = [&](int i) {
    return Vec3d(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  };
  for (int i = 0; i < 8; ++i)
    for (int bit = 1; bit < 8; bit <<= 1)
      if (!(i & bit)) edges.push_back({corner(i), corner(i | bit)});
  return edges;
}

std::vector<Segment3> plane_grid(const Vec3d& point, const Vec3d& normal, const Vec3d& centre, double half_size_m) {
  const Vec3d n = normal.normalized();
  // An orthonormal basis (u, v) of the plane (Duff et al. 2017, "Building an orthonormal basis, revisited").
  const double sign = std::copysign(1.0, n.z()), a = -1.0 / (sign + n.z()), b = n.x() * n.y() * a;
  const Vec3d u(1 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  const Vec3d v(b, sign + n.y() * n.y() * a, -n.y());
  const Vec3d c = centre - n * n.dot(centre - point);
  // Spacing: 1, 2 or 5 × 10^k, the largest not above a quarter of the half size (about 8 lines).
  const double raw = half_size_m / 4, decade = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw >= 5 * decade ? 5 * decade : raw >= 2 * decade ? 2 * decade : decade;
  const int k = int(std::floor(half_size_m / step));
  // Lines at multiples of the spacing in the plane's own coordinates, so the grid stays put as
  // the centre moves.
  const double cu = std::round(u.dot(c - point) / step) * step, cv = std::round(v.dot(c - point) / step) * step;
  const Vec3d origin = point + u * cu + v * cv;
  std::vector<Segment3> lines;
  for (int i = -k; i <= k; ++i) {
    lines.push_back({origin + u * (i * step) - v * (k * step), origin + u * (i * step) + v * (k * step)});
    lines.push_back({origin + v * (i * step) - u * (k * step), origin + v * (i * step) + u * (k * step)});
  }
  return lines;
}

std::optional<Segment2> project_segment(const Camera& camera, const Segment3& s) {
  // Clip at Z_c = ε·max|Z_c| in camera space: a segment crossing the camera's plane would
  // otherwise project through infinity to the wrong side.
  Vec3d a = camera.to_camera(s.a_world), b = camera.to_camera(s.b_world);
  const double eps = 1e-6 * std::max(std::abs(a.z()), std::abs(b.z()));
  if (a.z() <= eps && b.z() <= eps) return std::nullopt;
  if (a.z() <= eps) a = a + (b - a) * ((eps - a.z()) / (b.z() - a.z()));
  if (b.z() <= eps) b = b + (a - b) * ((eps - b.z()) / (a.z() - b.z()));
  const auto pixel = [&](const Vec3d& p) {
    return Vec2d(camera.fx * p.x() / p.z() + camera.cx, camera.fy * p.y() / p.z() + camera.cy);
  };
  return Segment2{pixel(a), pixel(b)};
}

}  // namespace insitu
