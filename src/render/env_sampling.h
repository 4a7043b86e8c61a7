// Importance sampling of the environment cube (issue 5): directions drawn with probability
// proportional to luminance × solid angle of the cube's texels.
//
// The cube is taken as constant per texel (the same piecewise-constant function the `exact`
// irradiance integrates; radiance() is the nearest-texel lookup). Texel i is chosen with
// probability P_i = w_i / Σw, with MIS compensation (Karlík et al. 2019): w_i = max(0, Y(L_i) − Ȳ)·ΔΩ_i,
// Ȳ the solid-angle mean of the luminance — the BSDF samples already cover the even part of the
// light, so the environment samples go where it stands out — plus a floor of 10⁻³ of the mean
// weight so that every texel can be drawn (a constant environment is sampled uniformly); within
// the texel a point is drawn uniformly on the face plane.
//
// A sampler may be restricted to part of the sphere (room_light.h: what the capture point saw on
// the walls, or through the openings): w_i is multiplied by the share of texel i in that part
// (`share`, 0…1; a texel across a window's edge is in both), which leaves the floor. Without
// the compensation (`mis_compensation` false) w_i = Y(L_i)·ΔΩ_i: for light that BSDF samples
// rarely reach, such as the sky through a window. For the face plane at distance 1, dω = dA / r³ (r = |point|), so the density in solid
// angle is
//   pdf(ω) = P_i · r³ / A_texel,   A_texel = (2/n)².
#pragma once
#include <functional>
#include <vector>

#include "light/cubemap.h"

namespace insitu {

struct EnvSample {
  Vec3f dir;        // unit
  float pdf;        // per steradian
};

class EnvSampler {
 public:
  // share(face, i, j) in [0, 1]: how much of the texel is drawn in proportion to its light.
  using TexelShare = std::function<double(int face, int i, int j)>;
  explicit EnvSampler(const CubeMap& radiance, const TexelShare& share = {}, bool mis_compensation = true);
  EnvSample sample(float u_texel, float u_s, float u_t) const;
  float pdf(const Vec3f& dir) const;
  Rgb radiance(const Vec3f& dir) const { return cube_->lookup_nearest(dir); }

 private:
  const CubeMap* cube_;
  int n_;
  std::vector<double> cdf_;   // 6n² + 1 entries, cdf_[0] = 0, cdf_.back() = 1
  std::vector<float> prob_;   // P_i
};

}  // namespace insitu
