// Directions toward the objects from a real surface: the objects as secondary light sources
// for the local scene (issue 50, "fewer speckles without bias").
//
// A wall point far from the furniture sees it in a small solid angle Ω. A cosine sample finds it
// with probability about Ω cos θ / π (2 % for a sofa 3 m away), and then adds the whole change it
// makes there, (L_object − L_behind)·ρ·π/cos θ·Ω-sized weight: at preview spp one pixel in a few
// of the whole photo gets such a hit, a speckle. Sampling the cones of the objects' bounding
// spheres as well finds them in every other sample (Shirley et al. 1996, "Monte Carlo techniques
// for direct lighting calculations", the cone of a spherical light; pbrt-v4's SampleUniformCone).
//
// Each object (a mesh) is bounded by a sphere (centre c_k, radius r_k); from x, sphere k spans
// the cone of half-angle θ_k with sin²θ_k = r_k² / |c_k − x|², solid angle
//   Ω_k = 2π (1 − cos θ_k),   1 − cos θ_k = sin²θ_k / (1 + cos θ_k)  (no cancellation when small).
// A cone is used at x when x lies outside the sphere and the sphere reaches above x's tangent
// plane. One is chosen in proportion to Ω_k and a direction drawn uniformly in it, so
//   p(ω) = #{k used : ω in cone k} / Σ_k Ω_k.
// More than kMaxCones objects are bounded in groups (sorted along x), so that each query stays a
// short loop.
#pragma once
#include <vector>

#include "render/mesh.h"

namespace insitu {

class ObjectCones {
 public:
  static constexpr int kMaxCones = 64;
  explicit ObjectCones(const std::vector<Mesh>& meshes);

  struct Sphere {
    Vec3f centre = Vec3f::Zero();
    float radius = 0;
  };
  const std::vector<Sphere>& spheres() const { return spheres_; }

  // Σ Ω_k over the cones used at x (normal n); 0: none (the strategy is not available there).
  float solid_angle(const Vec3f& x, const Vec3f& n) const;
  // A direction in the cones used at x, given their total solid angle (> 0).
  Vec3f sample(const Vec3f& x, const Vec3f& n, float total_sr, float u_pick, float u1, float u2) const;
  // The density of sample() at ω (unit), per steradian.
  float pdf(const Vec3f& x, const Vec3f& n, float total_sr, const Vec3f& dir) const;

 private:
  struct Cone {
    bool used = false;
    Vec3f axis = Vec3f::Zero();  // unit, from x to the centre
    float cos_max = 1, one_minus_cos = 0;
  };
  Cone cone(const Sphere& s, const Vec3f& x, const Vec3f& n) const;
  std::vector<Sphere> spheres_;
};

// The sampling of a real surface's reflected light (a Lambertian catcher at x, normal n): a
// cosine-weighted direction, or one toward the objects, with probability
//   s(x) = s_0 · max(0, 1 − Ω(x)/2π),   Ω(x) = Σ_k Ω_k over the cones used at x,
// so that where the objects fill the sky of x (under a table) the cosine, which finds them there
// anyway, keeps its samples; s_0 = 0 is the cosine alone, bit for bit. One sample from the mixture,
// whose density
//   p(ω) = (1 − s) max(0, n·ω)/π + s p_cones(ω)
// weighs every estimate taken along it (the one-sample balance heuristic, Veach 1997 §9.2.4), and
// stands for the reflection's strategy in the light sample's MIS weight.
class ReflectedSampling {
 public:
  ReflectedSampling(const ObjectCones& cones, float share, const Vec3f& x, const Vec3f& n);
  Vec3f sample(float u_pick, float u1, float u2) const;
  float pdf(const Vec3f& dir) const;
  float cone_share() const { return share_; }

 private:
  const ObjectCones& cones_;
  Vec3f x_, n_;
  float cones_sr_ = 0, share_ = 0;
};

}  // namespace insitu
