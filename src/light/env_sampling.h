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
// rarely reach, such as the sky through a window. For the face plane at distance 1,
// dω = dA / r³ (r = |point|), so the density in solid angle is
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
//
// The CDF is summed in double and kept in float, each entry rounded up to the float at or above
// it (4 bytes a texel, not 8: 25 MB less per sampler at a 1024 face). u is a float, and for a float
// u and a real c, u < c exactly when u < (the smallest float ≥ c): every u picks the texel the
// double CDF picks, bit for bit.
//
// A room's light keeps three samplers of nearly one cube (room_light.h: the whole cube, what the
// capture point saw on the walls and through the openings), which differ in their P_i everywhere
// but in their radiance only in the texels across an opening's edge. So a sampler may share
// another's records: it keeps only its P_i, with the sign bit set where its radiance differs from
// the other's, and those few texels' radiance aside (8.5 bytes a texel, not 20.5: at a 1024 face
// 76 MB less per sampler). Its radiance() then reads a second cache line, the other's record.
#pragma once
#include <cmath>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "light/cubemap.h"

namespace insitu {

struct EnvSample {
  Vec3f dir;  // unit
  float pdf;  // per steradian
};

// The radiance along a direction and the density of sampling it, found with one texel lookup.
struct EnvLookup {
  Rgb radiance;
  float pdf;  // per steradian
};

// The smallest float ≥ x (x finite): what a float compares with as with x itself.
float float_at_or_above(double x);

class EnvSampler {
 public:
  // share(face, i, j) in [0, 1]: how much of the texel is drawn in proportion to its light.
  using TexelShare = std::function<double(int face, int i, int j)>;
  explicit EnvSampler(const CubeMap& radiance, const TexelShare& share = {}, bool mis_compensation = true);
  // The same sampler of `radiance`, its radiance read from `records` (a sampler of its own records,
  // of a cube of the same size, which must outlive it) wherever the two cubes' texels are equal.
  EnvSampler(const CubeMap& radiance, const EnvSampler& records, const TexelShare& share, bool mis_compensation = true);
  EnvSample sample(float u_texel, float u_s, float u_t) const;
  // The same, with the texel found by bisection of the whole CDF: the obviously correct version.
  EnvSample sample_by_bisection(float u_texel, float u_s, float u_t) const;
  float pdf(const Vec3f& dir) const;
  // The cube's nearest texel (CubeMap::lookup_nearest, the same value).
  Rgb radiance(const Vec3f& dir) const;
  // radiance(dir) and pdf(dir), the same values, from one projection onto the cube.
  EnvLookup lookup(const Vec3f& dir) const;

 private:
  struct alignas(16) Texel {
    float rgb[3];
    float prob;  // P_i
  };
  std::size_t texel_of(int face, float s, float t) const;
  EnvSample sample_in(std::size_t k, float u_s, float u_t) const;
  float pdf_at(const FaceCoord& fc) const;
  // P_i from the cube's luminance and the shares, into prob(k) (a float&); the CDF and the guide.
  template <class ProbAt>
  void build(const CubeMap& radiance, const TexelShare& share, bool mis_compensation, ProbAt prob);
  float prob(std::size_t k) const { return records_ ? std::abs(prob_[k]) : texels_[k].prob; }
  Rgb rgb(std::size_t k) const;

  int n_;
  std::vector<Texel> texels_;  // by (face·n + j)·n + i; empty when records_ holds them
  // Sharing another sampler's records: P_i (negative where own_rgb_ holds the texel's radiance).
  const EnvSampler* records_ = nullptr;
  std::vector<float> prob_;
  std::vector<std::pair<std::uint32_t, Rgb>> own_rgb_;  // by texel index, ascending
  std::vector<float> cdf_;  // 6n² + 1 entries, cdf_[0] = 0, cdf_.back() = 1 (float_at_or_above)
  // G = 6n²/8 + 1 entries (small enough to stay in cache): guide_[g] is the first m with
  // cdf_[m] > g/G. The scan from there reads 8 entries of cdf_ on average, one cache line.
  static constexpr std::size_t kGuideSpan = 8;
  std::vector<std::uint32_t> guide_;
};

}  // namespace insitu
