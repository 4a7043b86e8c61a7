#include "light/env_sampling.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "light/texel_geometry.h"

namespace insitu {

float float_at_or_above(double x) {
  const float f = float(x);  // the nearest float
  return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

namespace {
// Texel k = (face·n + j)·n + i of the cube.
Rgb texel_k(const CubeMap& cube, std::size_t k) {
  const std::size_t n = std::size_t(cube.size());
  return cube.texel(int(k / (n * n)), int(k % n), int((k / n) % n));
}
}  // namespace

template <class ProbAt>
void EnvSampler::build(const CubeMap& radiance, const TexelShare& share, bool mis_compensation, ProbAt prob) {
  const std::size_t face_count = std::size_t(n_) * std::size_t(n_), count = 6 * face_count;
  const std::vector<double> omega = face_solid_angles(n_);  // by j·n + i, the same on every face
  // Texel k's luminance y_k waits in its P_k's place, and its weight w_k is computed from it again
  // in each pass rather than kept (8 bytes a texel: 50 MB at a 1024 face, when a room's light is
  // built beside its cube), the same value each time.
  double mean_y = 0;
  for (std::size_t k = 0; k < count; ++k) {
    prob(k) = std::max(0.0f, luminance(texel_k(radiance, k)));
    mean_y += double(prob(k)) * omega[k % face_count] / (4 * kPi);
  }
  auto weight = [&](std::size_t k) {
    const double w = std::max(0.0, double(prob(k)) - (mis_compensation ? mean_y : 0.0)) * omega[k % face_count];
    if (!share) return w;
    return w * share(int(k / face_count), int(k % std::size_t(n_)), int((k / std::size_t(n_)) % std::size_t(n_)));
  };
  double total = 0;
  for (std::size_t k = 0; k < count; ++k) total += weight(k);
  // A floor so that every texel can be drawn (also keeps a black environment well defined).
  const double floor = total > 0 ? 1e-3 * total / double(count) : 1.0;
  double sum = 0;
  for (std::size_t k = 0; k < count; ++k) sum += weight(k) + floor;
  cdf_.assign(count + 1, 0.0f);
  double cdf = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const double p = (weight(k) + floor) / sum;
    prob(k) = float(p);
    cdf += p;
    cdf_[k + 1] = float_at_or_above(cdf);
  }
  cdf_.back() = 1.0f;
  // guide_[g]: the first m ≥ 1 with cdf_[m] > g/G (what upper_bound gives for u = g/G).
  guide_.resize(count / kGuideSpan + 1);
  std::size_t m = 1;
  for (std::size_t g = 0; g < guide_.size(); ++g) {
    const double u = double(g) / double(guide_.size());
    while (m < count && !(u < cdf_[m])) ++m;
    guide_[g] = std::uint32_t(m);
  }
}

EnvSampler::EnvSampler(const CubeMap& radiance, const TexelShare& share, bool mis_compensation) : n_(radiance.size()) {
  texels_.resize(std::size_t(6) * std::size_t(n_) * std::size_t(n_));
  for (std::size_t k = 0; k < texels_.size(); ++k) {
    const Rgb L = texel_k(radiance, k);
    texels_[k] = {{L[0], L[1], L[2]}, 0.0f};
  }
  build(radiance, share, mis_compensation, [this](std::size_t k) -> float& { return texels_[k].prob; });
}

EnvSampler::EnvSampler(const CubeMap& radiance, const EnvSampler& records, const TexelShare& share,
                       bool mis_compensation)
    : n_(radiance.size()), records_(&records) {
  if (records.records_ || records.n_ != n_) throw std::logic_error("EnvSampler: records of another size, or shared");
  prob_.resize(std::size_t(6) * std::size_t(n_) * std::size_t(n_));
  build(radiance, share, mis_compensation, [this](std::size_t k) -> float& { return prob_[k]; });
  for (std::size_t k = 0; k < prob_.size(); ++k) {
    const Rgb L = texel_k(radiance, k);
    if (std::memcmp(L.data(), records.texels_[k].rgb, sizeof(float) * 3) == 0) continue;
    own_rgb_.emplace_back(std::uint32_t(k), L);
    prob_[k] = -prob_[k];  // P_i > 0 (the floor): the sign marks the texel
  }
}

Rgb EnvSampler::rgb(std::size_t k) const {
  const float* L = nullptr;
  if (!records_)
    L = texels_[k].rgb;
  else if (!std::signbit(prob_[k]))
    L = records_->texels_[k].rgb;
  else
    return std::lower_bound(own_rgb_.begin(), own_rgb_.end(), std::uint32_t(k),
                            [](const auto& e, std::uint32_t key) { return e.first < key; })
        ->second;
  return {L[0], L[1], L[2]};
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
  s.pdf = prob(k) * r * r * r / area;
  return s;
}

EnvSample EnvSampler::sample_by_bisection(float u_texel, float u_s, float u_t) const {
  const auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), u_texel);
  const std::size_t k = std::min<std::size_t>(std::size_t(it - cdf_.begin()) - 1, cdf_.size() - 2);
  return sample_in(k, u_s, u_t);
}

// The first m ≥ 1 with cdf_[m] > u, as upper_bound finds it: from the guide's entry for u, forward
// past entries ≤ u, then back while the one before is > u (the guide's g/G may round either side
// of u·G's floor). About kGuideSpan = 8 entries on average, one cache line of the CDF: the guide
// has one entry per 8 texels.
EnvSample EnvSampler::sample(float u_texel, float u_s, float u_t) const {
  const float u = u_texel;
  const double x = double(u) * double(guide_.size());
  const std::size_t g = x >= 0 ? std::min(guide_.size() - 1, std::size_t(x)) : 0;
  const std::size_t count = cdf_.size() - 1;
  std::size_t m = guide_[g];
  while (m <= count && !(u < cdf_[m])) ++m;
  while (m > 1 && u < cdf_[m - 1]) --m;
  return sample_in(std::min(m - 1, count - 1), u_s, u_t);
}

// pdf(ω) = P_i · r³ / A_texel, r the distance to the face plane's point (the header's comment).
float EnvSampler::pdf_at(const FaceCoord& fc) const {
  const Vec3f p = face_to_direction(fc.face, fc.s, fc.t);
  const float r = p.norm();
  return prob(texel_of(fc.face, fc.s, fc.t)) * r * r * r / (4.0f / float(n_ * n_));
}

float EnvSampler::pdf(const Vec3f& dir) const { return pdf_at(direction_to_face(dir)); }

Rgb EnvSampler::radiance(const Vec3f& dir) const {
  const FaceCoord fc = direction_to_face(dir);
  return rgb(texel_of(fc.face, fc.s, fc.t));
}

EnvLookup EnvSampler::lookup(const Vec3f& dir) const {
  const FaceCoord fc = direction_to_face(dir);
  return {rgb(texel_of(fc.face, fc.s, fc.t)), pdf_at(fc)};
}

}  // namespace insitu
