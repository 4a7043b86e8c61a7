// suggest_next_click (object_uncertainty.h): the floor point whose click would most reduce the
// variance at the objects.
//
// One more observation c with pixel noise σ̂ updates the parameter covariance C by Woodbury's
// identity (the information form C⁻¹ + J_cᵀJ_c/σ̂², with C singular in the parameters a model
// holds fixed):
//   C' = C − C J_cᵀ (J_c C J_cᵀ + σ̂² I)⁻¹ J_c C,
// and the variance at an object point x becomes tr(J_x C' J_xᵀ). The candidate with the smallest
// sum over the objects' points wins. The richer model's covariance is used when there is one: its
// extra parameters are what the clicks fail to pin down.
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <limits>

#include "calib/fit_state.h"
#include "calib/object_uncertainty.h"

namespace insitu {

using namespace calib_detail;

namespace {

using Mat10 = Eigen::Matrix<double, 10, 10>;
using Jac = Eigen::Matrix<double, 2, 10>;

Jac jacobian_norm(const ModelCovariance& m, const Frames& fr, const Vec3d& p_world) {
  return numeric_jacobian<2>(m.params, [&](const Params& q) { return project_norm(q, fr.to_norm(p_world)); });
}

Mat10 with_observation(const ModelCovariance& m, const Jac& Jc) {
  const Eigen::Matrix2d S = Jc * m.C * Jc.transpose() + m.sigma_norm * m.sigma_norm * Eigen::Matrix2d::Identity();
  return m.C - m.C * Jc.transpose() * S.inverse() * Jc * m.C;
}

// Candidates: a 24 × 18 grid of the photo's pixels, followed to the floor plane y = floor_y, and
// the objects' feet; each in front of the camera and inside the photo with a margin of 3 % (a
// click at the very edge is neither easy nor, with the camera's error, surely in the photo).
std::vector<Vec3d> floor_candidates(const CalibrationResult& r, const std::vector<ObjectUncertainty>& objects,
                                    double floor_y) {
  const Camera& cam = r.camera;
  std::vector<Vec3d> out;
  const Vec3d eye = cam.eye_world();
  for (int j = 0; j < 18; ++j)
    for (int i = 0; i < 24; ++i) {
      const Vec2d uv((i + 0.5) * cam.width / 24.0, (j + 0.5) * cam.height / 18.0);
      const Vec3d d = cam.unproject(uv, 1.0) - eye;
      const double t = (floor_y - eye.y()) / d.y();
      if (!(std::isfinite(t) && t > 0)) continue;
      Vec3d p = eye + t * d;
      p.y() = floor_y;  // exactly on the floor
      out.push_back(p);
    }
  for (const auto& o : objects)
    for (const auto& p : o.points)
      if (p.point.p_world.y() <= floor_y + 1e-9 * (1 + std::abs(floor_y))) out.push_back(p.point.p_world);
  std::vector<Vec3d> seen;
  for (const Vec3d& c : out) {
    double depth = 0;
    const Vec2d uv = cam.project(c, &depth);
    const double mx = 0.03 * cam.width, my = 0.03 * cam.height;
    if (depth > 0 && uv.x() >= mx && uv.y() >= my && uv.x() <= cam.width - mx && uv.y() <= cam.height - my)
      seen.push_back(c);
  }
  return seen;
}

}  // namespace

std::optional<ClickHint> suggest_next_click(const CalibrationResult& r, const std::vector<ObjectUncertainty>& objects) {
  if (!r.state) return std::nullopt;
  const CalibrationFitState& st = *r.state;
  const std::optional<ModelCovariance>& m = st.richer ? st.richer : st.chosen;
  if (!m) return std::nullopt;
  std::vector<Jac> Jx;  // the objects' points, in pixels per parameter
  double floor_y = std::numeric_limits<double>::infinity();
  for (const auto& o : objects)
    for (const auto& p : o.points) {
      Jx.push_back(jacobian_norm(*m, st.frames, p.point.p_world) * st.frames.image_scale);
      floor_y = std::min(floor_y, p.point.p_world.y());
    }
  if (Jx.empty()) return std::nullopt;
  auto worst_sigma = [&](const Mat10& C) {
    double v = 0;
    for (const Jac& J : Jx)
      v = std::max(v, Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(J * C * J.transpose()).eigenvalues().maxCoeff());
    return std::sqrt(std::max(0.0, v));
  };
  std::optional<ClickHint> best;
  double best_sum = std::numeric_limits<double>::infinity();
  for (const Vec3d& c : floor_candidates(r, objects, floor_y)) {
    const Mat10 C1 = with_observation(*m, jacobian_norm(*m, st.frames, c));
    double sum = 0;
    for (const Jac& J : Jx) sum += (J * C1 * J.transpose()).trace();
    if (!(sum < best_sum)) continue;
    best_sum = sum;
    best = ClickHint{c, r.camera.project(c), worst_sigma(m->C), worst_sigma(C1), model_name(m->model)};
  }
  return best;
}

}  // namespace insitu
