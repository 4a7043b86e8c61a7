#include "render/env_sampling.h"

#include <algorithm>

#include "light/texel_geometry.h"

namespace insitu {

EnvSampler::EnvSampler(const CubeMap& radiance, const TexelShare& share, bool mis_compensation)
    : cube_(&radiance), n_(radiance.size()) {
  const std::size_t count = std::size_t(6) * n_ * n_;
  const std::size_t face_count = std::size_t(n_) * std::size_t(n_);
  const std::vector<double> omega = face_solid_angles(n_);  // by j·n + i, the same on every face
  std::vector<double> w(count), y(count);
  double mean_y = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n_; ++j)
      for (int i = 0; i < n_; ++i) {
        const std::size_t k = (std::size_t(f) * n_ + j) * n_ + i;
        y[k] = std::max(0.0f, luminance(radiance.texel(f, i, j)));
        mean_y += y[k] * omega[k % face_count] / (4 * kPi);
      }
  double total = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const int f = int(k / face_count), j = int((k / std::size_t(n_)) % std::size_t(n_)), i = int(k % std::size_t(n_));
    w[k] = std::max(0.0, y[k] - (mis_compensation ? mean_y : 0.0)) * omega[k % face_count] * (share ? share(f, i, j) : 1.0);
    total += w[k];
  }
  // A floor so that every texel can be drawn (also keeps a black environment well defined).
  const double floor = total > 0 ? 1e-3 * total / double(count) : 1.0;
  cdf_.assign(count + 1, 0.0);
  prob_.resize(count);
  double sum = 0;
  for (std::size_t k = 0; k < count; ++k) sum += w[k] + floor;
  for (std::size_t k = 0; k < count; ++k) {
    prob_[k] = float((w[k] + floor) / sum);
    cdf_[k + 1] = cdf_[k] + (w[k] + floor) / sum;
  }
  cdf_.back() = 1.0;
}

EnvSample EnvSampler::sample(float u_texel, float u_s, float u_t) const {
  const auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), double(u_texel));
  const std::size_t k = std::min<std::size_t>(std::size_t(it - cdf_.begin()) - 1, prob_.size() - 1);
  const int i = int(k % std::size_t(n_)), j = int((k / std::size_t(n_)) % std::size_t(n_)), f = int(k / (std::size_t(n_) * n_));
  const Vec3f p = face_to_direction(f, (float(i) + u_s) / float(n_), (float(j) + u_t) / float(n_));
  const float r = p.norm();
  const float area = 4.0f / float(n_ * n_);
  EnvSample s;
  s.dir = p / r;
  s.pdf = prob_[k] * r * r * r / area;
  return s;
}

float EnvSampler::pdf(const Vec3f& dir) const {
  const FaceCoord fc = direction_to_face(dir);
  const int i = std::clamp(int(fc.s * float(n_)), 0, n_ - 1), j = std::clamp(int(fc.t * float(n_)), 0, n_ - 1);
  const Vec3f p = face_to_direction(fc.face, fc.s, fc.t);
  const float r = p.norm();
  return prob_[(std::size_t(fc.face) * n_ + j) * n_ + i] * r * r * r / (4.0f / float(n_ * n_));
}

}  // namespace insitu
