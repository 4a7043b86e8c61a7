#include "light/shot_gains.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace insitu {
namespace {

// The nearest pixel of shot s that sees direction d, if one does.
std::optional<std::pair<int, int>> pixel_of(const ShotSet& set, int s, const Vec3d& d) {
  const ShotBasis b = aimed_basis(set, s);
  const Image& img = set.shots[std::size_t(s)];
  const double z = d.dot(b.forward);
  if (z <= 1e-6 || img.empty()) return std::nullopt;
  const double f_px = 0.5 * img.width / std::tan(0.5 * deg_to_rad(set.hfov_deg[std::size_t(s)]));
  const double px = 0.5 * img.width + f_px * d.dot(b.right) / z, py = 0.5 * img.height - f_px * d.dot(b.up) / z;
  if (!(px >= 0 && px < img.width && py >= 0 && py < img.height)) return std::nullopt;
  return std::pair{int(px), int(py)};
}

bool usable(const ShotSet& set, const ShotSet* clipped, int s, std::pair<int, int> p) {
  const Rgb c = set.shots[std::size_t(s)].rgb(p.first, p.second);
  if (!(c.minCoeff() > 1e-6f) || !c.allFinite()) return false;
  return !clipped || clipped->shots[std::size_t(s)].empty() ||
         clipped->shots[std::size_t(s)].rgb(p.first, p.second).maxCoeff() < 0.5f;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

struct PairOffset {
  int a, b;
  Eigen::Array3d m;  // median log(I_b / I_a) per channel
};

// The pair's offset from a 64 × 48 grid of a's rays seen, unclipped, by both; none under 50.
std::optional<PairOffset> pair_offset(const ShotSet& set, const ShotSet* clipped, int a, int b) {
  const ShotBasis ba = aimed_basis(set, a);
  const double t = std::tan(0.5 * deg_to_rad(set.hfov_deg[std::size_t(a)]));
  const Image& img = set.shots[std::size_t(a)];
  const double aspect = img.width > 0 ? double(img.height) / img.width : 1.0;
  std::array<std::vector<double>, 3> logs;
  for (int j = 0; j < 48; ++j)
    for (int i = 0; i < 64; ++i) {
      const double x = (2 * (i + 0.5) / 64 - 1) * t, y = (1 - 2 * (j + 0.5) / 48) * t * aspect;
      const Vec3d d = (ba.forward + x * ba.right + y * ba.up).normalized();
      const auto pa = pixel_of(set, a, d), pb = pixel_of(set, b, d);
      if (!pa || !pb || !usable(set, clipped, a, *pa) || !usable(set, clipped, b, *pb)) continue;
      const Rgb ca = set.shots[std::size_t(a)].rgb(pa->first, pa->second);
      const Rgb cb = set.shots[std::size_t(b)].rgb(pb->first, pb->second);
      for (int c = 0; c < 3; ++c) logs[std::size_t(c)].push_back(std::log(double(cb[c]) / double(ca[c])));
    }
  if (logs[0].size() < 50) return std::nullopt;
  PairOffset p{a, b, {}};
  for (int c = 0; c < 3; ++c) p.m[c] = median(logs[std::size_t(c)]);
  return p;
}

}  // namespace

ShotPairs every_pair() {
  ShotPairs all;
  for (auto& row : all) row.fill(true);
  return all;
}

ShotPairs aimed_pairs(const Registration& registration, const LineAnchor* lines, const PhotoAnchor* photo) {
  std::array<bool, 6> absolute{};
  for (std::size_t f = 0; f < 6; ++f)
    absolute[f] = (lines && lines->axes == LineAxes::room && lines->anchored[f] && !lines->off_box[f]) ||
                  (photo && photo->anchored[f]);
  ShotPairs pairs{};
  for (std::size_t a = 0; a < 6; ++a)
    for (std::size_t b = 0; b < 6; ++b) {
      const ShotAim &sa = registration.shots[a], &sb = registration.shots[b];
      const bool together = sa.registered && sb.registered && registration.group[a] == registration.group[b];
      pairs[a][b] = together || (absolute[a] && absolute[b]);
    }
  return pairs;
}

ShotGains overlap_gains(const ShotSet& set, const ShotSet* clipped, const ShotPairs& comparable) {
  ShotGains out;
  std::vector<PairOffset> pairs;
  for (int a = 0; a < 6; ++a)
    for (int b = a + 1; b < 6; ++b)
      if (comparable[std::size_t(a)][std::size_t(b)])
        if (auto p = pair_offset(set, clipped, a, b)) pairs.push_back(*p);
  if (pairs.empty()) return out;
  // Normal equations of the least squares above, per channel: (JᵀJ) x = Jᵀr, x = log g.
  const double w_pair = 1 / (0.01 * 0.01), w_prior = 1;
  Eigen::Matrix<double, 6, 6> A = w_prior * Eigen::Matrix<double, 6, 6>::Identity();
  Eigen::Matrix<double, 6, 3> rhs = Eigen::Matrix<double, 6, 3>::Zero();
  for (const PairOffset& p : pairs) {
    // residual log g_a − log g_b − m_ab
    A(p.a, p.a) += w_pair, A(p.b, p.b) += w_pair, A(p.a, p.b) -= w_pair, A(p.b, p.a) -= w_pair;
    for (int c = 0; c < 3; ++c) rhs(p.a, c) += w_pair * p.m[c], rhs(p.b, c) -= w_pair * p.m[c];
    ++out.pairs[std::size_t(p.a)], ++out.pairs[std::size_t(p.b)];
  }
  Eigen::Matrix<double, 6, 3> x = A.ldlt().solve(rhs);
  for (int c = 0; c < 3; ++c) {
    std::vector<double> used;
    for (int s = 0; s < 6; ++s)
      if (out.pairs[std::size_t(s)] > 0) used.push_back(x(s, c));
    x.col(c).array() -= median(used);
  }
  for (int s = 0; s < 6; ++s)
    if (out.pairs[std::size_t(s)] > 0)
      out.gain[std::size_t(s)] = Rgb(float(std::exp(x(s, 0))), float(std::exp(x(s, 1))), float(std::exp(x(s, 2))));
  return out;
}

void apply_gains(ShotSet& set, const ShotGains& gains) {
  for (int s = 0; s < 6; ++s) {
    Image& img = set.shots[std::size_t(s)];
    const Rgb g = gains.gain[std::size_t(s)];
    if ((g == Rgb::Ones()).all()) continue;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) img.set_rgb(x, y, img.rgb(x, y) * g);
  }
}

}  // namespace insitu
