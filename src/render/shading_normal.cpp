#include "render/shading_normal.h"

#include <algorithm>
#include <cmath>

namespace insitu {

Vec3f tangent_space_normal(const Vec3f& n, const Vec4f& t, const Rgb& texel) {
  const Rgb m = 2.0f * texel - 1.0f;
  const Vec3f tangent = t.head<3>();
  const Vec3f b = t.w() * n.cross(tangent);
  const Vec3f sum = m[0] * tangent + m[1] * b + m[2] * n;
  return sum.squaredNorm() > 0 ? Vec3f(sum.normalized()) : Vec3f::Zero();
}

Vec3f with_strength(const Vec3f& n_s, const Vec3f& mapped, float strength) {
  if (strength == 1.0f) return mapped;
  const Vec3f sum = n_s + (mapped - n_s) * std::max(strength, 0.0f);
  return sum.squaredNorm() > 0 ? Vec3f(sum.normalized()) : Vec3f::Zero();
}

// In the frame of X (n's part orthogonal to ng) and Z = ng, the normal N' = (√(1 − z²), z) whose
// reflection R' = 2 (N'·I) N' − I has R'_z = t satisfies 2 (√(1 − z²) I_x + z I_z) z − I_z = t:
//   z² = (c ± b) / (2a),  a = I_x² + I_z²,  b = √(I_x² (a − t²)),  c = I_z t + a.
// Of the roots within (1e-5, 1 + 1e-5], the one whose reflection is the shallower positive one
// (the nearer to n) is taken, as Cycles does.
Vec3f valid_reflection_normal(const Vec3f& ng, const Vec3f& wo, const Vec3f& n) {
  const Vec3f r = 2.0f * n.dot(wo) * n - wo;
  const float threshold = std::min(0.9f * ng.dot(wo), 0.01f);
  if (ng.dot(r) >= threshold) return n;
  const Vec3f tangential = n - n.dot(ng) * ng;
  if (!(tangential.squaredNorm() > 0)) return ng;
  const Vec3f x = tangential.normalized();
  const float ix = wo.dot(x), iz = wo.dot(ng), ix2 = ix * ix;
  const float a = ix2 + iz * iz;
  if (!(a > 0)) return ng;
  const float b = std::sqrt(std::max(ix2 * (a - threshold * threshold), 0.0f));
  const float c = iz * threshold + a;
  const float z1 = 0.5f / a * (b + c), z2 = 0.5f / a * (c - b);
  bool valid1 = z1 > 1e-5f && z1 <= 1.0f + 1e-5f, valid2 = z2 > 1e-5f && z2 <= 1.0f + 1e-5f;
  auto unit = [](float z2_) { return Vec2f(std::sqrt(std::max(1.0f - z2_, 0.0f)), std::sqrt(std::max(z2_, 0.0f))); };
  Vec2f chosen;
  if (valid1 && valid2) {
    const Vec2f n1 = unit(z1), n2 = unit(z2);
    const float r1 = 2 * (n1.x() * ix + n1.y() * iz) * n1.y() - iz;
    const float r2 = 2 * (n2.x() * ix + n2.y() * iz) * n2.y() - iz;
    valid1 = r1 >= 1e-5f;
    valid2 = r2 >= 1e-5f;
    chosen = valid1 && valid2 ? (r1 < r2 ? n1 : n2) : (r1 > r2 ? n1 : n2);
  } else if (valid1 || valid2) {
    chosen = unit(valid1 ? z1 : z2);
  } else {
    return ng;
  }
  return chosen.x() * x + chosen.y() * ng;
}

}  // namespace insitu
