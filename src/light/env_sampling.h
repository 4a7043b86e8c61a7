// Importance sampling of the environment cube: directions drawn with probability
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
// rarely reach, such as the sky through a window. For the face plane at distance 1, dω = dA / r³ (r = |point|), so the
// density in solid angle is
//   pdf(ω) = P_i · r³ / A_texel,   A_texel = (2/n)².
//
// Memory, not arithmetic, is what these cost (perf, docs/performance.md: the loads of the cube's
// texel and of P_i missed the cache). So each texel's radiance and P_i share one 16-byte record
// (radiance() and pdf() of a direction touch one cache line), and sample() finds its texel with a
// guide table (Devroye 1986, §III.2.4; Chen & Asau 1974) instead of bisecting the whole CDF:
// guide[g] is where the CDF passes g/G, and a short scan from there ends on the texel
// std::upper_bound finds — the same texel, bit for bit (sample_by_bisection keeps that slow
// version, and the tests compare them). The expected scan is 6n²/G entries whatever the CDF's
// shape: an interval of u holds as many texels as it holds of the CDF's mass, on average.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "light/cubemap.h"

namespace insitu {

struct EnvSample {
  Vec3f dir;  // unit
  float pdf;  // per steradian
};

class EnvSampler {
 public:
  // share(face, i, j) in [0, 1]: how much of the texel is drawn in proportion to its light.
  using TexelShare = std::function<double(int face, int i, int j)>;
  explicit EnvSampler(const CubeMap& radiance, const TexelShare& share = {}, bool mis_compensation = true);
  EnvSample sample(float u_texel, float u_s, float u_t) const;
  // The same, with the texel found by bisection of the whole CDF: the obviously correct version.
  EnvSample sample_by_bisection(float u_texel, float u_s, float u_t) const;
  float pdf(const Vec3f& dir) const;
  // The cube's nearest texel (CubeMap::lookup_nearest, the same value).
  Rgb radiance(const Vec3f& dir) const;

 private:
  struct alignas(16) Texel {
    float rgb[3];
    float prob;  // P_i
  };
  std::size_t texel_of(int face, float s, float t) const;
  EnvSample sample_in(std::size_t k, float u_s, float u_t) const;

  int n_;
  std::vector<Texel> texels_;  // by (face·n + j)·n + i
  std::vector<double> cdf_;    // 6n² + 1 entries, cdf_[0] = 0, cdf_.back() = 1
  // G = 6n²/8 + 1 entries (small enough to stay in cache): guide_[g] is the first m with
  // cdf_[m] > g/G. The scan from there reads 8 entries of cdf_ on average, one cache line.
  static constexpr std::size_t kGuideSpan = 8;
  std::vector<std::uint32_t> guide_;
};

}  // namespace insitu
