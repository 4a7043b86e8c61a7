#include "light/room_lines.h"

#include <fmt/format.h>

#include <ceres/ceres.h>
#include <ceres/rotation.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "light/rotation_prior.h"
#include "light/shot_features.h"

namespace insitu {
namespace {

// A segment's plane through the eye: its unit normal in the world (as the shot is aimed) and its
// length in pixels.
struct LinePlane {
  Vec3d n;
  double length_px;
};

// The shot's segments longer than 3 % of its diagonal, as planes.
std::vector<LinePlane> line_planes(const Image& shot, double hfov_deg, const ShotBasis& aimed) {
  Mat3d B;
  B.col(0) = aimed.right, B.col(1) = aimed.up, B.col(2) = aimed.forward;
  const MatchImage m = match_image(shot, hfov_deg, B, 1200);
  const cv::Mat log_y(m.log_y.height, m.log_y.width, CV_32F, const_cast<float*>(m.log_y.data.data()));
  const cv::Mat img = stretched_8bit(log_y, cv::Mat());
  std::vector<cv::Vec4f> segments;
  cv::createLineSegmentDetector(cv::LSD_REFINE_STD)->detect(img, segments);
  std::vector<LinePlane> out;
  const double w = img.cols, h = img.rows, min_px = 0.03 * std::hypot(w, h);
  const auto ray = [&](double x, double y) {
    return Vec3d(B * Vec3d((x + 0.5 - 0.5 * w) / m.f_px, -(y + 0.5 - 0.5 * h) / m.f_px, 1.0));
  };
  for (const cv::Vec4f& s : segments) {
    const double length = std::hypot(s[2] - s[0], s[3] - s[1]);
    if (length < min_px) continue;
    const Vec3d n = ray(s[0], s[1]).cross(ray(s[2], s[3]));
    if (n.norm() > 0) out.push_back({n.normalized(), length});
  }
  return out;
}

// The axis a segment is along under rotation G: the one whose component of G n is smallest, if
// under the gate and if no second axis is within 3 × of it (a plane holding two axes).
int axis_of(const LinePlane& l, const Mat3d& G, double gate) {
  const Vec3d c = (G * l.n).cwiseAbs();
  int k = 0;
  for (int a = 1; a < 3; ++a)
    if (c[a] < c[k]) k = a;
  const double second = std::min(c[(k + 1) % 3], c[(k + 2) % 3]);
  return (c[k] < gate && second > 3 * std::max(c[k], std::sin(deg_to_rad(0.5)))) ? k : -1;
}

struct AxisResidual {
  Vec3d n;
  int k;
  double scale;  // √(w / mean w) / σ
  template <typename T>
  bool operator()(const T* w, T* r) const {
    const T p[3] = {T(n[0]), T(n[1]), T(n[2])};
    T q[3];
    ceres::AngleAxisRotatePoint(w, p, q);
    r[0] = q[k] * T(scale);
    return true;
  }
};

struct Fit {
  std::array<double, 3> w{};
  double sigma_deg = 0;  // the standard deviation of the turn along its own axis
};

// σ of ω along the turn's axis: Ceres's covariance of the fit, scaled by the residuals' own
// spread (the reduced χ², Σ r² / (m − 3)) rather than the assumed σ.
double turn_sigma_deg(ceres::Problem& problem, std::array<double, 3>& w, const ceres::Solver::Summary& summary,
                      int dof) {
  ceres::Covariance::Options options;
  ceres::Covariance covariance(options);
  std::vector<std::pair<const double*, const double*>> blocks = {{w.data(), w.data()}};
  if (!covariance.Compute(blocks, &problem)) return 1e9;
  Eigen::Matrix3d C;
  covariance.GetCovarianceBlock(w.data(), w.data(), C.data());
  const int m = problem.NumResiduals();
  const double chi2 = m > 3 + dof ? 2 * summary.final_cost / (m - 3 - dof) : 1.0;  // 3 prior residuals
  const Vec3d v(w[0], w[1], w[2]);
  const Vec3d axis = v.norm() > 0 ? Vec3d(v.normalized()) : Vec3d::UnitX();
  return rad_to_deg(std::sqrt(std::max(0.0, chi2 * axis.dot(C.transpose() * axis))));
}

// One round: the segments assigned under G's current value, and G fitted to them. With
// LineAxes::vertical only the segments along y are residuals, and ω_y is held at 0.
Fit fit_round(const std::vector<LinePlane>& lines, std::array<double, 3> w, double gate, LineAxes axes) {
  const Mat3d G = rotation_of(w);
  double mean_length = 0;
  for (const LinePlane& l : lines) mean_length += l.length_px / double(lines.size());
  ceres::Problem problem;
  for (const LinePlane& l : lines) {
    const int k = axis_of(l, G, gate);
    if (k < 0 || (axes == LineAxes::vertical && k != 1)) continue;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<AxisResidual, 1, 3>(new AxisResidual{
                                 l.n, k, std::sqrt(l.length_px / mean_length) / std::sin(deg_to_rad(0.5))}),
                             new ceres::CauchyLoss(1.0), w.data());
  }
  problem.AddResidualBlock(
      new ceres::AutoDiffCostFunction<RotationPrior, 3, 3>(new RotationPrior{1.0 / deg_to_rad(10.0)}), nullptr,
      w.data());
  if (axes == LineAxes::vertical) problem.SetManifold(w.data(), new ceres::SubsetManifold(3, {1}));
  ceres::Solver::Options options;
  options.max_num_iterations = 30;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return {w, turn_sigma_deg(problem, w, summary, axes == LineAxes::vertical ? 2 : 3)};
}

void anchor_group(const std::vector<int>& shots, const std::array<std::vector<LinePlane>, 6>& planes, LineAxes axes,
                  LineAnchor& out);

// A group the room box's axes would turn by `turn_deg`, past a hand's misaim: levelled by the same
// segments' plumb lines instead, as without a box (LineAnchor::off_box).
void level_off_box_group(const std::vector<int>& shots, const std::array<std::vector<LinePlane>, 6>& planes,
                         double turn_deg, LineAnchor& out) {
  for (int s : shots) out.lines[std::size_t(s)] = {};
  anchor_group(shots, planes, LineAxes::vertical, out);
  const std::string why = fmt::format(
      "its lines run {:.1f}° off the room box's axes, more than a hand misaims ({:.0f}°): is the box drawn along the "
      "walls?",
      turn_deg, kMaxHandTurnDeg);
  for (int s : shots) {
    const auto i = std::size_t(s);
    out.off_box[i] = true;
    out.off_box_turn_deg[i] = turn_deg;
    out.reason[i] = out.anchored[i] ? why : why + "; and " + out.reason[i];
  }
}

// The group's rotation, or none with the reason.
void anchor_group(const std::vector<int>& shots, const std::array<std::vector<LinePlane>, 6>& planes, LineAxes axes,
                  LineAnchor& out) {
  std::vector<LinePlane> lines;
  for (int s : shots) lines.insert(lines.end(), planes[std::size_t(s)].begin(), planes[std::size_t(s)].end());
  Fit fit;
  for (double gate_deg : {6.0, 3.0, 2.0}) fit = fit_round(lines, fit.w, std::sin(deg_to_rad(gate_deg)), axes);
  const std::array<double, 3>& w = fit.w;
  const Mat3d G = rotation_of(w);
  std::array<int, 3> along{};
  for (int s : shots) {
    for (const LinePlane& l : planes[std::size_t(s)])
      if (const int k = axis_of(l, G, std::sin(deg_to_rad(2.0))); k >= 0) ++out.lines[std::size_t(s)][std::size_t(k)];
    for (int k = 0; k < 3; ++k) along[std::size_t(k)] += out.lines[std::size_t(s)][std::size_t(k)];
  }
  const int vertical = along[1];
  std::sort(along.begin(), along.end());
  const bool enough = axes == LineAxes::vertical ? vertical >= 10 : along[1] >= 10;
  const double turn_deg = rad_to_deg(Vec3d(w[0], w[1], w[2]).norm());
  if (enough && axes == LineAxes::room && turn_deg > kMaxHandTurnDeg) {
    level_off_box_group(shots, planes, turn_deg, out);
    return;
  }
  for (int s : shots) {
    if (!enough) {
      out.reason[std::size_t(s)] = axes == LineAxes::vertical ? "too few vertical lines to level it"
                                                              : "too few straight lines along two of the room's axes";
      continue;
    }
    out.anchored[std::size_t(s)] = true;
    out.sigma_deg[std::size_t(s)] = fit.sigma_deg;
    if (turn_deg < 3 * fit.sigma_deg) continue;  // within the lines' own precision: not a misaim
    out.turn_deg[std::size_t(s)] = turn_deg;
    out.correction[std::size_t(s)] = G;
  }
}

}  // namespace

LineAnchor anchor_to_room_axes(const ShotSet& set, const std::array<int, 6>& group, LineAxes axes) {
  std::array<std::vector<LinePlane>, 6> planes;
  tbb::parallel_for(0, 6, [&](int s) {
    planes[std::size_t(s)] = line_planes(set.shots[std::size_t(s)], set.hfov_deg[std::size_t(s)], aimed_basis(set, s));
  });
  LineAnchor out;
  out.axes = axes;
  std::array<bool, 6> done{};
  for (int s = 0; s < 6; ++s) {
    if (done[std::size_t(s)]) continue;
    std::vector<int> shots;
    for (int t = 0; t < 6; ++t)
      if (group[std::size_t(t)] == group[std::size_t(s)]) shots.push_back(t), done[std::size_t(t)] = true;
    anchor_group(shots, planes, axes, out);
  }
  return out;
}

}  // namespace insitu
