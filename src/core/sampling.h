// Sampling helpers every integrator shares: the shading frame, cosine-weighted
// directions, the power heuristic and the ray offset. One copy of each, tested in
// tests/sampling_test.cpp.
#pragma once
#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace insitu {

// An orthonormal frame (t, b, n) around a unit normal n (Frisvad-style choice of the helper axis:
// x unless n is close to it).
struct Frame {
  Vec3f t, b, n;
  explicit Frame(const Vec3f& normal) : n(normal) {
    t = (std::abs(n.x()) < 0.9f ? Vec3f(1, 0, 0) : Vec3f(0, 1, 0)).cross(n).normalized();
    b = n.cross(t);
  }
  Vec3f to_local(const Vec3f& v) const { return {v.dot(t), v.dot(b), v.dot(n)}; }
  Vec3f to_world(const Vec3f& v) const { return v.x() * t + v.y() * b + v.z() * n; }
};

// A cosine-weighted direction about +z by Malley's method (a uniform point on the unit disk,
// projected up): pdf(ω) = cos θ / π.
inline Vec3f cosine_sample_local(float u1, float u2) {
  const float r = std::sqrt(u1), phi = 2 * kPiF * u2;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1 - u1))};
}

// The same about a unit normal n, in the world frame.
inline Vec3f cosine_sample(const Vec3f& n, float u1, float u2) {
  return Frame(n).to_world(cosine_sample_local(u1, u2)).normalized();
}

// A uniform direction over the upper hemisphere (z = u1): pdf(ω) = 1 / 2π.
inline Vec3f uniform_hemisphere_local(float u1, float u2) {
  const float r = std::sqrt(std::max(0.0f, 1 - u1 * u1)), phi = 2 * kPiF * u2;
  return {r * std::cos(phi), r * std::sin(phi), u1};
}

// Veach's power heuristic (β = 2) for strategy a against b (Veach 1997, §9.2.4):
// w_a = p_a² / (p_a² + p_b²); w_a + w_b = 1.
inline float power_heuristic(float pdf_a, float pdf_b) { return pdf_a * pdf_a / (pdf_a * pdf_a + pdf_b * pdf_b); }

// Where a ray leaves a surface: p + n_g·ε with ε = 10⁻⁵·max(1 mm, |p|_∞), relative to the
// position's magnitude, so that objects of a millimetre and of a kilometre are treated alike
// (docs/conventions.md, "Ray offsets").
inline Vec3f offset_origin(const Vec3f& p, const Vec3f& ng) {
  const float eps = 1e-5f * std::max(1e-3f, p.cwiseAbs().maxCoeff());
  return p + eps * ng;
}

}  // namespace insitu
