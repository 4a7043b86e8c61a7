#include "light/texel_geometry.h"

#include <cmath>

#include "light/cubemap.h"

namespace insitu {

namespace {
double area_element(double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0)); }

Vec3d face_point(int face, double s, double t) {
  // face_to_direction in double precision: the same table (cubemap.h), not normalized.
  const double sc = 2 * s - 1, tc = 2 * t - 1;
  switch (face) {
    case kPosX:
      return {1, -tc, -sc};
    case kNegX:
      return {-1, -tc, sc};
    case kPosY:
      return {sc, 1, tc};
    case kNegY:
      return {sc, -1, -tc};
    case kPosZ:
      return {sc, -tc, 1};
    default:
      return {-sc, -tc, -1};
  }
}
}  // namespace

double texel_solid_angle(int i, int j, int n) {
  const double x0 = 2.0 * i / n - 1, x1 = 2.0 * (i + 1) / n - 1;
  const double y0 = 2.0 * j / n - 1, y1 = 2.0 * (j + 1) / n - 1;
  return area_element(x0, y0) - area_element(x0, y1) - area_element(x1, y0) + area_element(x1, y1);
}

std::vector<double> face_solid_angles(int n) {
  std::vector<double> corner(std::size_t(n + 1) * std::size_t(n + 1));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      corner[std::size_t(j) * std::size_t(n + 1) + std::size_t(i)] = area_element(2.0 * i / n - 1, 2.0 * j / n - 1);
  auto a = [&](int i, int j) { return corner[std::size_t(j) * std::size_t(n + 1) + std::size_t(i)]; };
  std::vector<double> omega(std::size_t(n) * std::size_t(n));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      omega[std::size_t(j) * std::size_t(n) + std::size_t(i)] = a(i, j) - a(i, j + 1) - a(i + 1, j) + a(i + 1, j + 1);
  return omega;
}

std::vector<Vec3d> texel_corners(int face, int i, int j, int n) {
  const double s0 = double(i) / n, s1 = double(i + 1) / n, t0 = double(j) / n, t1 = double(j + 1) / n;
  return {face_point(face, s0, t0), face_point(face, s1, t0), face_point(face, s1, t1), face_point(face, s0, t1)};
}

Vec3d polygon_vector_irradiance(const std::vector<Vec3d>& v) {
  Vec3d phi = Vec3d::Zero(), centre = Vec3d::Zero();
  const std::size_t k = v.size();
  for (std::size_t a = 0; a < k; ++a) {
    const Vec3d& p = v[a];
    const Vec3d& q = v[(a + 1) % k];
    const Vec3d c = p.cross(q);
    const double cn = c.norm();
    centre += p.normalized();
    if (cn == 0) continue;
    // Θ = atan2(|p × q|, p·q): accurate for tiny and for large angles alike.
    phi += std::atan2(cn, p.dot(q)) * (c / cn);
  }
  phi *= 0.5;
  // Orientation: Γ must point toward the polygon.
  return phi.dot(centre) < 0 ? Vec3d(-phi) : phi;
}

Vec3d texel_vector_irradiance(int face, int i, int j, int n) {
  return polygon_vector_irradiance(texel_corners(face, i, j, n));
}

double texel_clamped_cosine_integral(int face, int i, int j, int n, const Vec3d& normal) {
  const std::vector<Vec3d> quad = texel_corners(face, i, j, n);
  int above = 0;
  for (const auto& p : quad) above += normal.dot(p) >= 0;
  if (above == 0) return 0;
  if (above == 4) return normal.dot(polygon_vector_irradiance(quad));
  // Sutherland–Hodgman against the half-space n·x >= 0.
  std::vector<Vec3d> clipped;
  for (std::size_t a = 0; a < 4; ++a) {
    const Vec3d& p = quad[a];
    const Vec3d& q = quad[(a + 1) % 4];
    const double dp = normal.dot(p), dq = normal.dot(q);
    if (dp >= 0) clipped.push_back(p);
    if ((dp >= 0) != (dq >= 0)) clipped.push_back(p + (q - p) * (dp / (dp - dq)));
  }
  if (clipped.size() < 3) return 0;
  return std::max(0.0, normal.dot(polygon_vector_irradiance(clipped)));
}

}  // namespace insitu
