#include "light/shot_registration.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "light/rotation_prior.h"
#include "light/shot_features.h"

namespace insitu {
namespace {

// The verified matches a pair needs to count: 2.5 times RANSAC's minimal sample (4 for a
// homography), and after the first fit still that many that one rotation explains (a rotation
// needs 2).
constexpr std::size_t kMinMatches = 10;

Mat3d basis_matrix(const ShotBasis& b) {
  Mat3d B;
  B.col(0) = b.right, B.col(1) = b.up, B.col(2) = b.forward;
  return B;
}

// (R_a u_a − R_b u_b) / σ_m: the chord between the two rays once aimed, ≈ their angle.
struct MatchResidual {
  Vec3d u_a, u_b;
  double inv_sigma;
  template <typename T>
  bool operator()(const T* aa_a, const T* aa_b, T* r) const {
    const T ua[3] = {T(u_a[0]), T(u_a[1]), T(u_a[2])}, ub[3] = {T(u_b[0]), T(u_b[1]), T(u_b[2])};
    T wa[3], wb[3];
    ceres::AngleAxisRotatePoint(aa_a, ua, wa);
    ceres::AngleAxisRotatePoint(aa_b, ub, wb);
    for (int k = 0; k < 3; ++k) r[k] = (wa[k] - wb[k]) * T(inv_sigma);
    return true;
  }
};

struct PairMatches {
  int a, b;
  std::vector<RayPair> rays;
};

// The pairs worth matching, and their verified matches (in parallel over pairs).
std::vector<PairMatches> match_pairs(const ShotSet& set, const std::array<MatchImage, 6>& images, double min_overlap) {
  std::vector<PairMatches> pairs;
  for (int a = 0; a < 6; ++a)
    for (int b = a + 1; b < 6; ++b)
      if (std::max(nominal_overlap(set, a, b), nominal_overlap(set, b, a)) >= min_overlap) pairs.push_back({a, b, {}});
  tbb::parallel_for(std::size_t(0), pairs.size(), [&](std::size_t k) {
    PairMatches& p = pairs[k];
    p.rays = verified_matches(images[std::size_t(p.a)], images[std::size_t(p.b)]);
    if (p.rays.size() < kMinMatches) p.rays.clear();
  });
  return pairs;
}

// The bundle adjustment over the shots that have matches; the others keep a zero rotation.
std::array<std::array<double, 3>, 6> solve_aims(const std::vector<PairMatches>& pairs,
                                                const std::array<MatchImage, 6>& images, const RegistrationOptions& o) {
  std::array<std::array<double, 3>, 6> aa{};
  ceres::Problem problem;
  std::array<bool, 6> used{};
  for (const PairMatches& p : pairs)
    for (const RayPair& m : p.rays) {
      const double inv_sigma = std::min(images[std::size_t(p.a)].f_px, images[std::size_t(p.b)].f_px);
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<MatchResidual, 3, 3, 3>(new MatchResidual{m.u_a, m.u_b, inv_sigma}),
          new ceres::CauchyLoss(2.0), aa[std::size_t(p.a)].data(), aa[std::size_t(p.b)].data());
      used[std::size_t(p.a)] = used[std::size_t(p.b)] = true;
    }
  for (int s = 0; s < 6; ++s)
    if (used[std::size_t(s)])
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<RotationPrior, 3, 3>(new RotationPrior{1.0 / deg_to_rad(o.prior_sigma_deg)}),
          nullptr, aa[std::size_t(s)].data());
  if (problem.NumResidualBlocks() == 0) return aa;
  ceres::Solver::Options options;
  options.max_num_iterations = 50;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return aa;
}

// The angle between a match's rays once aimed, in degrees.
double match_angle_deg(const RayPair& m, const Mat3d& R_a, const Mat3d& R_b) {
  const Vec3d wa = R_a * m.u_a, wb = R_b * m.u_b;
  return rad_to_deg(std::atan2(wa.cross(wb).norm(), wa.dot(wb)));
}

// Matches that RANSAC's homography (8 degrees of freedom, where a rotation has 3) let through
// but the rotations do not explain: farther than max(0.25°, 4 × the median) after the first fit.
// A pair left with fewer than kMinMatches is dropped.
void drop_outliers(std::vector<PairMatches>& pairs, const std::array<std::array<double, 3>, 6>& aa) {
  std::array<Mat3d, 6> R;
  for (int s = 0; s < 6; ++s) R[std::size_t(s)] = rotation_of(aa[std::size_t(s)]);
  std::vector<double> angles;
  for (const PairMatches& p : pairs)
    for (const RayPair& m : p.rays) angles.push_back(match_angle_deg(m, R[std::size_t(p.a)], R[std::size_t(p.b)]));
  if (angles.empty()) return;
  std::nth_element(angles.begin(), angles.begin() + std::ptrdiff_t(angles.size() / 2), angles.end());
  const double limit = std::max(0.25, 4 * angles[angles.size() / 2]);
  for (PairMatches& p : pairs) {
    p.rays.erase(std::remove_if(p.rays.begin(), p.rays.end(),
                                [&](const RayPair& m) {
                                  return match_angle_deg(m, R[std::size_t(p.a)], R[std::size_t(p.b)]) > limit;
                                }),
                 p.rays.end());
    if (p.rays.size() < kMinMatches) p.rays.clear();
  }
}

// Each shot's report: its rotation, split along its own axes, and the residual of its matches.
void describe(const std::vector<PairMatches>& pairs, const std::array<std::array<double, 3>, 6>& aa,
              const std::array<Mat3d, 6>& B, Registration& r) {
  std::array<double, 6> sum_sq{};
  for (const PairMatches& p : pairs)
    for (const RayPair& m : p.rays) {
      const double angle = match_angle_deg(m, r.aim[std::size_t(p.a)], r.aim[std::size_t(p.b)]);
      for (int s : {p.a, p.b}) {
        sum_sq[std::size_t(s)] += angle * angle;
        ++r.shots[std::size_t(s)].matches;
      }
    }
  for (int s = 0; s < 6; ++s) {
    ShotAim& a = r.shots[std::size_t(s)];
    describe_aim(rotation_of(aa[std::size_t(s)]),
                 ShotBasis{B[std::size_t(s)].col(2), B[std::size_t(s)].col(1), B[std::size_t(s)].col(0)}, a);
    if (a.matches > 0) a.residual_deg = std::sqrt(sum_sq[std::size_t(s)] / a.matches);
  }
}

// Shots joined by a pair's matches share a group (both registered).
void join_groups(const std::vector<PairMatches>& pairs, Registration& r) {
  for (bool changed = true; changed;) {
    changed = false;
    for (const PairMatches& p : pairs) {
      if (p.rays.empty() || !r.shots[std::size_t(p.a)].registered || !r.shots[std::size_t(p.b)].registered) continue;
      const int g = std::min(r.group[std::size_t(p.a)], r.group[std::size_t(p.b)]);
      for (int s : {p.a, p.b})
        if (r.group[std::size_t(s)] != g) r.group[std::size_t(s)] = g, changed = true;
    }
  }
}

}  // namespace

void describe_aim(const Mat3d& aim, const ShotBasis& nominal, ShotAim& a) {
  const Eigen::AngleAxisd aa(aim);
  const Vec3d v = aa.angle() * aa.axis();
  a.rotation_deg = rad_to_deg(aa.angle());
  a.pitch_deg = rad_to_deg(v.dot(nominal.right)), a.yaw_deg = rad_to_deg(v.dot(nominal.up));
  a.roll_deg = rad_to_deg(v.dot(nominal.forward));
}

double nominal_overlap(const ShotSet& set, int a, int b) {
  const ShotBasis ba = shot_basis(a, set.faced_face), bb = shot_basis(b, set.faced_face);
  const auto half_tans = [&](int s) {
    const double t = std::tan(0.5 * deg_to_rad(set.hfov_deg[std::size_t(s)]));
    const Image& img = set.shots[std::size_t(s)];
    return std::pair{t, img.width > 0 ? t * img.height / img.width : t};
  };
  const auto [tx_a, ty_a] = half_tans(a);
  const auto [tx_b, ty_b] = half_tans(b);
  const int n = 24;
  int inside = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = (2 * (i + 0.5) / n - 1) * tx_a, y = (2 * (j + 0.5) / n - 1) * ty_a;
      const Vec3d d = ba.forward + x * ba.right + y * ba.up;
      const double z = d.dot(bb.forward);
      if (z > 0 && std::abs(d.dot(bb.right) / z) < tx_b && std::abs(d.dot(bb.up) / z) < ty_b) ++inside;
    }
  return double(inside) / (n * n);
}

Registration register_shots(const ShotSet& set, const RegistrationOptions& o) {
  Registration r;
  std::array<Mat3d, 6> B;
  for (int s = 0; s < 6; ++s) B[std::size_t(s)] = basis_matrix(shot_basis(s, set.faced_face));
  std::array<bool, 6> overlaps{};
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b)
      if (a != b && std::max(nominal_overlap(set, a, b), nominal_overlap(set, b, a)) >= o.min_overlap)
        overlaps[std::size_t(a)] = r.overlap = true;
  std::array<MatchImage, 6> images;
  tbb::parallel_for(0, 6, [&](int s) {
    if (overlaps[std::size_t(s)])
      images[std::size_t(s)] =
          match_image(set.shots[std::size_t(s)], set.hfov_deg[std::size_t(s)], B[std::size_t(s)], o.max_side_px);
  });
  std::vector<PairMatches> pairs = match_pairs(set, images, o.min_overlap);
  drop_outliers(pairs, solve_aims(pairs, images, o));
  const auto aa = solve_aims(pairs, images, o);
  for (int s = 0; s < 6; ++s) r.aim[std::size_t(s)] = rotation_of(aa[std::size_t(s)]);
  describe(pairs, aa, B, r);
  for (int s = 0; s < 6; ++s) {
    ShotAim& a = r.shots[std::size_t(s)];
    if (!overlaps[std::size_t(s)]) {
      a.reason = fmt::format("its {:.0f}° view overlaps no neighbour's", set.hfov_deg[std::size_t(s)]);
    } else if (a.matches == 0) {
      a.reason = "no features agree with a neighbour's (too plain, too dark, or too far off its nominal direction)";
    } else if (a.rotation_deg > o.max_rotation_deg) {
      a.reason = fmt::format("the fit turns it {:.0f}°, more than a misaim", a.rotation_deg);
    } else {
      a.registered = true;
      continue;
    }
    r.aim[std::size_t(s)] = Mat3d::Identity();  // the nominal direction
    a.rotation_deg = a.yaw_deg = a.pitch_deg = a.roll_deg = 0;
  }
  join_groups(pairs, r);
  return r;
}

}  // namespace insitu
