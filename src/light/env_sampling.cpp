#include "light/env_sampling.h"

#include <algorithm>
#include <cmath>

#include "light/texel_geometry.h"

namespace insitu {

EnvSampler::EnvSampler(const CubeMap& radiance, const TexelShare& share, bool mis_compensation) : n_(radiance.size()) {
  const std::size_t count = std::size_t(6) * n_ * n_;
  const std::size_t face_count = std::size_t(n_) * std::size_t(n_);
  const std::vector<double> omega = face_solid_angles(n_);  // by j·n + i, the same on every face
  // Texel k's luminance y_k is kept in texels_[k].prob and its weight w_k in cdf_[k + 1] until the
  // last pass: no temporary arrays (a sampler of a 256² cube is 10 MB, built several times a load).
  texels_.resize(count);
  cdf_.assign(count + 1, 0.0);
  double mean_y = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t f = k / face_count, j = (k / std::size_t(n_)) % std::size_t(n_), i = k % std::size_t(n_);
    const Rgb L = radiance.texel(int(f), int(i), int(j));
    texels_[k] = {{L[0], L[1], L[2]}, std::max(0.0f, luminance(L))};
    mean_y += double(texels_[k].prob) * omega[k % face_count] / (4 * kPi);
  }
  double total = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const int f = int(k / face_count), j = int((k / std::size_t(n_)) % std::size_t(n_)), i = int(k % std::size_t(n_));
    const double y = texels_[k].prob;
    cdf_[k + 1] =
        std::max(0.0, y - (mis_compensation ? mean_y : 0.0)) * omega[k % face_count] * (share ? share(f, i, j) : 1.0);
    total += cdf_[k + 1];
  }
  // A floor so that every texel can be drawn (also keeps a black environment well defined).
  const double floor = total > 0 ? 1e-3 * total / double(count) : 1.0;
  double sum = 0;
  for (std::size_t k = 0; k < count; ++k) sum += cdf_[k + 1] + floor;
  for (std::size_t k = 0; k < count; ++k) {
    const double p = (cdf_[k + 1] + floor) / sum;
    texels_[k].prob = float(p);
    cdf_[k + 1] = cdf_[k] + p;
  }
  cdf_.back() = 1.0;
  // guide_[g]: the first m ≥ 1 with cdf_[m] > g/G (what upper_bound gives for u = g/G).
  guide_.resize(count / kGuideSpan + 1);
  std::size_t m = 1;
  for (std::size_t g = 0; g < guide_.size(); ++g) {
    const double u = double(g) / double(guide_.size());
    while (m < count && !(u < cdf_[m])) ++m;
    guide_[g] = std::uint32_t(m);
  }
}

// The texel of face coordinates (s, t) ∈ [0, 1]²: the nearest one, as CubeMap::lookup_nearest.
std::size_t EnvSampler::texel_of(int face, float s, float t) const {
  const int i = nearest_texel_index(s, n_), j = nearest_texel_index(t, n_);
  return (std::size_t(face) * std::size_t(n_) + std::size_t(j)) * std::size_t(n_) + std::size_t(i);
}

// A point drawn uniformly on texel k's face square, and its density in solid angle.
EnvSample EnvSampler::sample_in(std::size_t k, float u_s, float u_t) const {
  const int i = int(k % std::size_t(n_)), j = int((k / std::size_t(n_)) % std::size_t(n_)),
            f = int(k / (std::size_t(n_) * n_));
  const Vec3f p = face_to_direction(f, (float(i) + u_s) / float(n_), (float(j) + u_t) / float(n_));
  const float r = p.norm();
  const float area = 4.0f / float(n_ * n_);
  EnvSample s;
  s.dir = p / r;
  s.pdf = texels_[k].prob * r * r * r / area;
  return s;
}

EnvSample EnvSampler::sample_by_bisection(float u_texel, float u_s, float u_t) const {
  const auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), double(u_texel));
  const std::size_t k = std::min<std::size_t>(std::size_t(it - cdf_.begin()) - 1, texels_.size() - 1);
  return sample_in(k, u_s, u_t);
}

// The first m ≥ 1 with cdf_[m] > u, as upper_bound finds it: from the guide's entry for u, forward
// past entries ≤ u, then back while the one before is > u (the guide's g/G may round either side
// of u·G's floor). About kGuideSpan = 8 entries on average, one cache line of the CDF: the guide
// has one entry per 8 texels.
EnvSample EnvSampler::sample(float u_texel, float u_s, float u_t) const {
  const double u = double(u_texel), x = u * double(guide_.size());
  const std::size_t g = x >= 0 ? std::min(guide_.size() - 1, std::size_t(x)) : 0;
  const std::size_t count = texels_.size();
  std::size_t m = guide_[g];
  while (m <= count && !(u < cdf_[m])) ++m;
  while (m > 1 && u < cdf_[m - 1]) --m;
  return sample_in(std::min(m - 1, count - 1), u_s, u_t);
}

float EnvSampler::pdf(const Vec3f& dir) const {
  const FaceCoord fc = direction_to_face(dir);
  const Vec3f p = face_to_direction(fc.face, fc.s, fc.t);
  const float r = p.norm();
  return texels_[texel_of(fc.face, fc.s, fc.t)].prob * r * r * r / (4.0f / float(n_ * n_));
}

Rgb EnvSampler::radiance(const Vec3f& dir) const {
  const FaceCoord fc = direction_to_face(dir);
  const float* L = texels_[texel_of(fc.face, fc.s, fc.t)].rgb;
  return {L[0], L[1], L[2]};
}

}  // namespace insitu
