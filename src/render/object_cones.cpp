#include "render/object_cones.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/sampling.h"

namespace insitu {
namespace {

// The sphere about the box centre of the triangles' vertices of `meshes`, through the farthest.
ObjectCones::Sphere bounding_sphere(const std::vector<const Mesh*>& meshes) {
  Vec3f lo = Vec3f::Constant(std::numeric_limits<float>::infinity()), hi = -lo;
  auto each_vertex = [&](auto&& f) {
    for (const Mesh* m : meshes)
      for (const Triangle& t : m->triangles)
        for (std::uint32_t v : t.v) f(m->positions[v]);
  };
  each_vertex([&](const Vec3f& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); });
  ObjectCones::Sphere s;
  if (!(lo.array() <= hi.array()).all()) return s;  // no triangles
  s.centre = 0.5f * (lo + hi);
  float r2 = 0;
  each_vertex([&](const Vec3f& p) { r2 = std::max(r2, (p - s.centre).squaredNorm()); });
  s.radius = std::sqrt(r2) * (1 + 1e-5f);  // the vertices strictly inside, whatever the rounding
  return s;
}

Vec3f box_centre(const Mesh& m) {
  Vec3f lo = Vec3f::Constant(std::numeric_limits<float>::infinity()), hi = -lo;
  for (const Triangle& t : m.triangles)
    for (std::uint32_t v : t.v) lo = lo.cwiseMin(m.positions[v]), hi = hi.cwiseMax(m.positions[v]);
  return (lo.array() <= hi.array()).all() ? Vec3f(0.5f * (lo + hi)) : Vec3f::Zero();
}

}  // namespace

ObjectCones::ObjectCones(const std::vector<Mesh>& meshes) {
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < meshes.size(); ++k)
    if (!meshes[k].triangles.empty()) order.push_back(k);
  std::vector<float> x(meshes.size());
  for (std::size_t k : order) x[k] = box_centre(meshes[k]).x();
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  // Groups of consecutive meshes along x, as even as kMaxCones allows (one mesh each when few).
  const std::size_t groups = std::min<std::size_t>(order.size(), kMaxCones);
  for (std::size_t g = 0; g < groups; ++g) {
    std::vector<const Mesh*> group;
    for (std::size_t k = g * order.size() / groups; k < (g + 1) * order.size() / groups; ++k)
      group.push_back(&meshes[order[k]]);
    const Sphere s = bounding_sphere(group);
    if (s.radius > 0) spheres_.push_back(s);
  }
}

// Below this sin²θ an object is too far (10⁻⁴ of its radius) for its cone to matter, and its
// density 1/Ω would pass 10⁸.
constexpr float kMinSin2 = 1e-8f;

ObjectCones::Cone ObjectCones::cone(const Sphere& s, const Vec3f& x, const Vec3f& n) const {
  Cone c;
  const Vec3f v = s.centre - x;
  const float d2 = v.squaredNorm(), r2 = s.radius * s.radius;
  if (!(d2 > r2) || !(n.dot(v) > -s.radius)) return c;  // inside, or wholly below the tangent plane
  const float sin2 = r2 / d2;
  if (!(sin2 > kMinSin2)) return c;
  c.used = true;
  c.axis = v / std::sqrt(d2);
  c.cos_max = std::sqrt(std::max(0.0f, 1 - sin2));
  c.one_minus_cos = sin2 / (1 + c.cos_max);
  return c;
}

float ObjectCones::solid_angle(const Vec3f& x, const Vec3f& n) const {
  float total = 0;
  for (const Sphere& s : spheres_)
    if (const Cone c = cone(s, x, n); c.used) total += 2 * kPiF * c.one_minus_cos;
  return total;
}

// Uniform in the chosen cone: 1 − cos θ = u1 (1 − cos θ_max), φ = 2π u2.
Vec3f ObjectCones::sample(const Vec3f& x, const Vec3f& n, float total_sr, float u_pick, float u1, float u2) const {
  float target = u_pick * total_sr, acc = 0;
  Cone chosen;
  for (const Sphere& s : spheres_) {
    const Cone c = cone(s, x, n);
    if (!c.used) continue;
    chosen = c;
    acc += 2 * kPiF * c.one_minus_cos;
    if (target < acc) break;
  }
  const float one_minus_cos = u1 * chosen.one_minus_cos;
  const float cos_t = 1 - one_minus_cos;
  const float sin_t = std::sqrt(std::max(0.0f, one_minus_cos * (2 - one_minus_cos)));
  const float phi = 2 * kPiF * u2;
  return Frame(chosen.axis).to_world({sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t}).normalized();
}

float ObjectCones::pdf(const Vec3f& x, const Vec3f& n, float total_sr, const Vec3f& dir) const {
  if (!(total_sr > 0)) return 0.0f;
  int inside = 0;
  for (const Sphere& s : spheres_)
    if (const Cone c = cone(s, x, n); c.used && dir.dot(c.axis) >= c.cos_max) ++inside;
  return float(inside) / total_sr;
}

ReflectedSampling::ReflectedSampling(const ObjectCones& cones, float share, const Vec3f& x, const Vec3f& n)
    : cones_(cones), x_(x), n_(n) {
  if (!(share > 0)) return;
  cones_sr_ = cones.solid_angle(x, n);
  share_ = cones_sr_ > 0 ? share * std::max(0.0f, 1 - cones_sr_ / (2 * kPiF)) : 0.0f;
}

Vec3f ReflectedSampling::sample(float u_pick, float u1, float u2) const {
  if (u_pick < share_)
    return cones_.sample(x_, n_, cones_sr_, std::min(u_pick / share_, std::nextafter(1.0f, 0.0f)), u1, u2);
  return cosine_sample(n_, u1, u2);
}

float ReflectedSampling::pdf(const Vec3f& dir) const {
  const float p_cos = std::max(0.0f, n_.dot(dir)) / kPiF;
  if (!(share_ > 0)) return p_cos;
  return (1 - share_) * p_cos + share_ * cones_.pdf(x_, n_, cones_sr_, dir);
}

}  // namespace insitu
