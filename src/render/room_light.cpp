#include "render/room_light.h"

#include <cmath>
#include <limits>

namespace insitu {

RoomLight::RoomLight(const EnvSampler& env, bool box, const Vec3f& box_min, const Vec3f& box_max, const Vec3f& capture)
    : env_(&env), box_(box), min_(box_min), max_(box_max), capture_(capture) {}

bool RoomLight::inside(const Vec3f& x) const {
  return (x.array() > min_.array()).all() && (x.array() < max_.array()).all();
}

bool RoomLight::exit(const Vec3f& p, const Vec3f& dir, float* t, int* axis) const {
  float t_exit = std::numeric_limits<float>::infinity();
  int a = -1;
  for (int k = 0; k < 3; ++k) {
    if (dir[k] == 0) continue;
    const float tk = ((dir[k] > 0 ? max_[k] : min_[k]) - p[k]) / dir[k];
    if (tk < t_exit) t_exit = tk, a = k;
  }
  if (a < 0 || !(t_exit > 0) || !std::isfinite(t_exit)) return false;
  *t = t_exit;
  *axis = a;
  return true;
}

RoomSample RoomLight::sample(const Vec3f& x, float u_texel, float u_s, float u_t) const {
  const EnvSample es = env_->sample(u_texel, u_s, u_t);
  RoomSample out;
  if (!box_ || !inside(x)) {
    out = {es.dir, std::numeric_limits<float>::infinity(), es.pdf, env_->radiance(es.dir)};
    return out;
  }
  float t_c = 0;
  int axis = 0;
  if (!exit(capture_, es.dir, &t_c, &axis)) return out;
  const Vec3f q = capture_ + t_c * es.dir, d = q - x;
  const float dist = d.norm();
  if (!(dist > 0)) return out;
  out.dir = d / dist;
  out.distance = dist;
  // cos θ_c = |ω_c[axis]|, cos θ_x = |ω[axis]|: the face's normal is that axis.
  const float cos_c = std::abs(es.dir[axis]), cos_x = std::abs(out.dir[axis]);
  out.pdf = cos_x > 0 ? es.pdf * cos_c / (t_c * t_c) * (dist * dist) / cos_x : 0.0f;
  out.radiance = env_->radiance(es.dir);
  return out;
}

float RoomLight::pdf(const Vec3f& x, const Vec3f& dir) const {
  if (!box_ || !inside(x)) return env_->pdf(dir);
  float t_x = 0;
  int axis = 0;
  if (!exit(x, dir, &t_x, &axis)) return 0.0f;
  const Vec3f v = x + t_x * dir - capture_;
  const float t_c = v.norm();
  if (!(t_c > 0)) return 0.0f;
  const Vec3f w_c = v / t_c;
  const float cos_c = std::abs(w_c[axis]), cos_x = std::abs(dir[axis]);
  return cos_x > 0 ? env_->pdf(w_c) * cos_c / (t_c * t_c) * (t_x * t_x) / cos_x : 0.0f;
}

Rgb RoomLight::radiance(const Vec3f& x, const Vec3f& dir) const {
  if (!box_ || !inside(x)) return env_->radiance(dir);
  float t_x = 0;
  int axis = 0;
  if (!exit(x, dir, &t_x, &axis)) return env_->radiance(dir);
  const Vec3f v = x + t_x * dir - capture_;
  return env_->radiance(v.squaredNorm() > 0 ? Vec3f(v.normalized()) : dir);
}

}  // namespace insitu
