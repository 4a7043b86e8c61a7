// The room as an emitter (issue 12, item 1): with a room box, the box's faces carry the six
// shots' radiance, projected from the capture point c, and are sampled as an area light.
//
// A point q on the box emits toward the room what the capture point saw in its direction:
// L(q) = cube(ω_c), ω_c = (q − c)/|q − c| (the box projection of real-time engines). Sampling
// draws ω_c from the cube's own distribution (env_sampling.h, density p_ω per steradian at c),
// follows it to the box at q, and converts to the shading point x:
//   area density on the box   p_A(q) = p_ω(ω_c) · cos θ_c / |q − c|²
//   solid angle at x          p_x(ω) = p_A(q) · |q − x|² / cos θ_x
// with θ_c, θ_x the angles between the face normal at q and the directions to c and to x. The
// radiance found along a direction and the density of drawing it then describe the same emitter,
// so bright texels are drawn where they light x (a cube sampled as seen from c, but looked up
// through the box, gives fireflies: its pdf has nothing to do with what arrives at x).
// A point outside the box sees the cube as distant light (by direction).
#pragma once
#include "render/env_sampling.h"

namespace insitu {

struct RoomSample {
  Vec3f dir = Vec3f::Zero();  // unit, from x toward the sampled point
  float distance = 0;         // to the sampled point on the box
  float pdf = 0;              // per steradian at x
  Rgb radiance = Rgb::Zero();
};

class RoomLight {
 public:
  // Without a box (`box` false) every call is the distant cube's.
  RoomLight(const EnvSampler& env, bool box, const Vec3f& box_min, const Vec3f& box_max, const Vec3f& capture);
  RoomSample sample(const Vec3f& x, float u_texel, float u_s, float u_t) const;
  float pdf(const Vec3f& x, const Vec3f& dir) const;       // of sample() producing dir at x
  Rgb radiance(const Vec3f& x, const Vec3f& dir) const;     // arriving at x along dir
  // The distance from p to the box along dir, and the axis of the face it leaves through (p inside).
  bool exit(const Vec3f& p, const Vec3f& dir, float* t, int* axis) const;

 private:
  bool inside(const Vec3f& x) const;
  const EnvSampler* env_;
  bool box_;
  Vec3f min_, max_, capture_;
};

}  // namespace insitu
