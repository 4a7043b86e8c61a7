// Importance sampling of the environment cube (issue 5): directions drawn with probability
// proportional to luminance × solid angle of the cube's texels.
//
// The cube is taken as constant per texel (the same piecewise-constant function the `exact`
// irradiance integrates; radiance() is the nearest-texel lookup). Texel i is chosen with
// probability P_i = w_i / Σw, with MIS compensation (Karlík et al. 2019): w_i = max(0, Y(L_i) − Ȳ)·ΔΩ_i,
// Ȳ the solid-angle mean of the luminance — the BSDF samples already cover the even part of the
// light, so the environment samples go where it stands out — plus a floor of 10⁻³ of the mean
// weight so that every texel can be drawn (a constant environment is sampled uniformly); within
// the texel a point is drawn uniformly on the face plane. For the face plane at distance 1, dω = dA / r³ (r = |point|), so the density in solid
// angle is
//   pdf(ω) = P_i · r³ / A_texel,   A_texel = (2/n)².
#pragma once
#include <vector>

#include "light/cubemap.h"

namespace insitu {

struct EnvSample {
  Vec3f dir;        // unit
  float pdf;        // per steradian
};

class EnvSampler {
 public:
  explicit EnvSampler(const CubeMap& radiance);
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
