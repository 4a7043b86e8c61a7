#include "calib/calibration.h"

#include <ceres/ceres.h>
#include <ceres/covariance.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <numeric>
#include <opencv2/calib3d.hpp>

#include "core/error.h"
#include "calib/f_test.h"
#include "calib/reprojection_cost.h"

namespace insitu {

const char* model_name(CameraModel m) {
  switch (m) {
    case CameraModel::kF: return "f";
    case CameraModel::kFC: return "f+c";
    default: return "f+c+a";
  }
}

std::optional<CameraModel> parse_model(const std::string& s) {
  if (s == "f") return CameraModel::kF;
  if (s == "f+c") return CameraModel::kFC;
  if (s == "f+c+a") return CameraModel::kFCA;
  return std::nullopt;
}

int model_parameter_count(CameraModel m) { return m == CameraModel::kF ? 7 : m == CameraModel::kFC ? 9 : 10; }

namespace {

constexpr double kExactFitPx = 1e-6;     // an RMS below this is a numerically exact fit
constexpr double kCauchyScalePx = 2.0;   // robust loss scale for the outlier search
constexpr double kOutlierMinPx = 3.0;    // never call a residual below this an outlier

// ---- Normalized frames ------------------------------------------------------------------------

struct Frames {
  Vec2d image_centre;  // (W/2, H/2)
  double image_scale;  // max(W, H)/2 pixels per normalized unit
  Vec3d world_centre;  // centroid of the points
  double world_scale;  // RMS distance of the points from it
  Vec2d to_norm(const Vec2d& uv) const { return (uv - image_centre) / image_scale; }
  Vec3d to_norm(const Vec3d& p) const { return (p - world_centre) / world_scale; }
};

// The parameters in normalized frames: p_cam = R(aa)·p_norm + t; intrinsics [f, cx, cy, a].
struct Params {
  double aa[3] = {0, 0, 0};
  double t[3] = {0, 0, 1};
  double intr[4] = {1, 0, 0, 1};
};

void constrain(Params& p, CameraModel model) {
  if (model == CameraModel::kF) { p.intr[1] = p.intr[2] = 0; }
  if (model != CameraModel::kFCA) p.intr[3] = 1;
}

Mat3d rotation_of(const Params& p) {
  const Vec3d aa(p.aa[0], p.aa[1], p.aa[2]);
  const double angle = aa.norm();
  return angle > 0 ? Eigen::AngleAxisd(angle, aa / angle).toRotationMatrix() : Mat3d::Identity();
}

void set_rotation(Params& p, const Mat3d& R) {
  const Eigen::AngleAxisd a(R);
  const Vec3d v = a.axis() * a.angle();
  for (int k = 0; k < 3; ++k) p.aa[k] = v[k];
}

// Back to pixels and world units: p_cam(world units) = s_w (R (p − c)/s_w + t) = R p + (s_w t − R c).
Camera to_camera(const Params& p, const Frames& fr, int width, int height) {
  Camera cam;
  cam.width = width;
  cam.height = height;
  cam.fx = p.intr[0] * fr.image_scale;
  cam.fy = p.intr[3] * p.intr[0] * fr.image_scale;
  cam.cx = fr.image_centre.x() + p.intr[1] * fr.image_scale;
  cam.cy = fr.image_centre.y() + p.intr[2] * fr.image_scale;
  cam.R_cam_from_world = rotation_of(p);
  cam.t_cam_from_world = fr.world_scale * Vec3d(p.t[0], p.t[1], p.t[2]) - cam.R_cam_from_world * fr.world_centre;
  return cam;
}

struct NormPoint {
  Vec2d uv;
  Vec3d p;
};

Vec2d project_norm(const Params& p, const Vec3d& x, double* depth = nullptr) {
  const Vec3d c = rotation_of(p) * x + Vec3d(p.t[0], p.t[1], p.t[2]);
  if (depth) *depth = c.z();
  return {p.intr[0] * c.x() / c.z() + p.intr[1], p.intr[3] * p.intr[0] * c.y() / c.z() + p.intr[2]};
}

double rss_norm(const Params& p, const std::vector<NormPoint>& pts) {
  double s = 0;
  for (const auto& q : pts) s += (project_norm(p, q.p) - q.uv).squaredNorm();
  return s;
}

// ---- Least squares (Ceres) -------------------------------------------------------------------

struct FitOutcome {
  Params params;
  double cost = 0;  // Ceres's cost: ½ Σ ρ(r²)
  bool converged = false;
};

FitOutcome refine(Params start, CameraModel model, const std::vector<NormPoint>& pts, double cauchy_scale_norm) {
  constrain(start, model);
  ceres::Problem problem;
  for (const auto& q : pts) {
    ceres::LossFunction* loss = cauchy_scale_norm > 0 ? new ceres::CauchyLoss(cauchy_scale_norm) : nullptr;
    problem.AddResidualBlock(ReprojectionCost::Create(q.uv, q.p), loss, start.aa, start.t, start.intr);
  }
  if (model == CameraModel::kF) problem.SetManifold(start.intr, new ceres::SubsetManifold(4, {1, 2, 3}));
  else if (model == CameraModel::kFC) problem.SetManifold(start.intr, new ceres::SubsetManifold(4, {3}));
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 200;
  options.function_tolerance = 1e-16;
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = 1e-16;
  options.logging_type = ceres::SILENT;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return {start, summary.final_cost, summary.IsSolutionUsable()};
}

// ---- Starting points ---------------------------------------------------------------------------

// DLT (Hartley & Zisserman §7.1) in the normalized frames: the 3×4 P minimizing |A p| with
// |p| = 1, then P = K [R | t] by RQ decomposition of its left 3×3.
std::optional<Params> dlt_start(const std::vector<NormPoint>& pts, CameraModel model) {
  const int n = int(pts.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 12);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector4d X(pts[i].p.x(), pts[i].p.y(), pts[i].p.z(), 1.0);
    A.block<1, 4>(2 * i, 0) = X.transpose();
    A.block<1, 4>(2 * i, 8) = -pts[i].uv.x() * X.transpose();
    A.block<1, 4>(2 * i + 1, 4) = X.transpose();
    A.block<1, 4>(2 * i + 1, 8) = -pts[i].uv.y() * X.transpose();
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd v = svd.matrixV().col(11);
  Eigen::Matrix<double, 3, 4> P;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) P(r, c) = v(4 * r + c);
  Mat3d M = P.leftCols<3>();
  if (M.determinant() < 0) { P = -P; M = -M; }
  if (!(std::abs(M.determinant()) > 1e-300)) return std::nullopt;
  // RQ: with the row-reversal J, QR of (J M)ᵀ = Q U gives M = (J Uᵀ J)(J Qᵀ).
  Mat3d J;
  J << 0, 0, 1, 0, 1, 0, 1, 0, 0;
  Eigen::HouseholderQR<Mat3d> qr((J * M).transpose());
  const Mat3d Q = qr.householderQ();
  const Mat3d U = qr.matrixQR().triangularView<Eigen::Upper>();
  Mat3d K = J * U.transpose() * J, R = J * Q.transpose();
  const Mat3d D = Vec3d(K(0, 0) < 0 ? -1 : 1, K(1, 1) < 0 ? -1 : 1, K(2, 2) < 0 ? -1 : 1).asDiagonal();
  K = K * D;
  R = D * R;
  if (R.determinant() < 0) return std::nullopt;
  const Vec3d t = K.inverse() * P.col(3);
  K /= K(2, 2);
  Params p;
  set_rotation(p, R);
  for (int k = 0; k < 3; ++k) p.t[k] = t[k];
  p.intr[0] = 0.5 * (K(0, 0) + K(1, 1));
  p.intr[1] = K(0, 2);
  p.intr[2] = K(1, 2);
  p.intr[3] = K(1, 1) / K(0, 0);
  if (model == CameraModel::kFCA) p.intr[0] = K(0, 0);
  constrain(p, model);
  // Points must lie in front.
  int front = 0;
  for (const auto& q : pts) {
    double z = 0;
    project_norm(p, q.p, &z);
    front += z > 0;
  }
  if (front * 2 < n || !(p.intr[0] > 0)) return std::nullopt;
  return p;
}

// PnP at a fixed focal length (principal point at the centre, square pixels), over a sweep of
// horizontal fields of view from 1° to 170°. Works for coplanar points and for five.
std::vector<Params> focal_sweep_starts(const std::vector<NormPoint>& pts, double half_width_norm) {
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (const auto& q : pts) {
    object.emplace_back(q.p.x(), q.p.y(), q.p.z());
    image.emplace_back(q.uv.x(), q.uv.y());
  }
  std::vector<std::pair<double, Params>> scored;
  const int steps = 48;
  const double lo = std::log(std::tan(deg_to_rad(0.5))), hi = std::log(std::tan(deg_to_rad(85.0)));
  for (int i = 0; i < steps; ++i) {
    const double tan_half = std::exp(lo + (hi - lo) * i / (steps - 1));
    const double f = half_width_norm / tan_half;
    const cv::Matx33d K(f, 0, 0, 0, f, 0, 0, 0, 1);
    cv::Vec3d rvec, tvec;
    bool ok = false;
    try {
      ok = cv::solvePnP(object, image, K, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_SQPNP);
    } catch (const cv::Exception&) {
      ok = false;
    }
    if (!ok) continue;
    Params p;
    for (int k = 0; k < 3; ++k) { p.aa[k] = rvec[k]; p.t[k] = tvec[k]; }
    p.intr[0] = f;
    double worst_depth = 1;
    std::vector<double> r;
    for (const auto& q : pts) {
      double z = 0;
      r.push_back((project_norm(p, q.p, &z) - q.uv).norm());
      worst_depth = std::min(worst_depth, z);
    }
    if (!std::isfinite(worst_depth)) continue;
    std::nth_element(r.begin(), r.begin() + long(r.size() / 2), r.end());
    scored.push_back({r[r.size() / 2], p});  // the median residual: robust to an outlier
  }
  std::sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Params> out;
  for (std::size_t i = 0; i < scored.size() && i < 4; ++i) out.push_back(scored[i].second);
  return out;
}

// ---- Checks of the point set -----------------------------------------------------------------

struct Geometry {
  Eigen::Vector3d singular;  // of the centred points
};

Geometry point_geometry(const std::vector<ControlPoint>& pts, const Vec3d& centre) {
  Eigen::MatrixXd X(pts.size(), 3);
  for (std::size_t i = 0; i < pts.size(); ++i) X.row(long(i)) = (pts[i].p_world - centre).transpose();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(X);
  return {svd.singularValues()};
}

std::string join_names(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

CalibrationResult calibrate(const std::vector<ControlPoint>& points, int width, int height,
                            const CalibrationOptions& options) {
  CalibrationResult result;
  const int n = int(points.size());
  if (n < 5) throw InputError("", fmt::format("{} control point(s): calibration needs at least 5", n));
  if (width < 1 || height < 1) throw InputError("", "image size must be positive");
  for (const auto& p : points)
    if (!p.uv_px.allFinite() || !p.p_world.allFinite()) throw InputError(p.where, fmt::format("point {} is not finite", p.name));
  // Clicked pixels lie in the image: points outside it mean the wrong image size (or origin).
  std::string outside;
  int n_outside = 0;
  for (const auto& p : points)
    if (p.uv_px.x() < 0 || p.uv_px.y() < 0 || p.uv_px.x() > width || p.uv_px.y() > height)
      outside += (n_outside++ < 5 ? fmt::format("{}{} ({:.1f}, {:.1f})", outside.empty() ? "" : ", ", p.name, p.uv_px.x(),
                                                p.uv_px.y())
                                  : "");
  if (n_outside > 0)
    throw InputError("", fmt::format("{} point(s) outside the {}x{} image: {}{} — is the image size (or the origin) right?",
                                     n_outside, width, height, outside, n_outside > 5 ? ", ..." : ""));

  // Normalized frames.
  Frames fr;
  fr.image_centre = Vec2d(0.5 * width, 0.5 * height);
  fr.image_scale = 0.5 * std::max(width, height);
  fr.world_centre = Vec3d::Zero();
  for (const auto& p : points) fr.world_centre += p.p_world / n;
  double ms = 0;
  for (const auto& p : points) ms += (p.p_world - fr.world_centre).squaredNorm() / n;
  fr.world_scale = std::sqrt(ms);

  // Degenerate point sets.
  const Geometry geo = point_geometry(points, fr.world_centre);
  if (!(fr.world_scale > 0) || geo.singular[1] <= 1e-9 * geo.singular[0])
    throw InputError("", "the control points are coincident or collinear: they cannot determine a camera");
  result.coplanar = geo.singular[2] <= 1e-6 * geo.singular[0];
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      if ((points[i].p_world - points[j].p_world).norm() <= 1e-9 * fr.world_scale)
        result.warnings.push_back(fmt::format("points {} and {} have the same 3D position", points[i].name, points[j].name));
      else if ((points[i].uv_px - points[j].uv_px).norm() <= 1e-6 * fr.image_scale)
        result.warnings.push_back(fmt::format("points {} and {} were clicked at the same pixel", points[i].name, points[j].name));
    }

  std::vector<NormPoint> norm;
  for (const auto& p : points) norm.push_back({fr.to_norm(p.uv_px), fr.to_norm(p.p_world)});
  const double half_width_norm = 0.5 * width / fr.image_scale;

  // Models this many points can support at all.
  auto supports = [&](CameraModel m, int count) { return 2 * count - model_parameter_count(m) >= 0; };
  if (options.model && !supports(*options.model, n))
    throw InputError("", fmt::format("{} points cannot determine model {} ({} parameters need at least {} points)", n,
                                     model_name(*options.model), model_parameter_count(*options.model),
                                     (model_parameter_count(*options.model) + 1) / 2));
  if (options.model && *options.model != CameraModel::kF && result.coplanar)
    result.warnings.push_back(fmt::format("the points are coplanar: one view of a plane cannot separate the principal "
                                          "point from the pose, so model {} is poorly determined", model_name(*options.model)));

  // 1. Starts, refined with the robust loss under model f; keep the best.
  const double cauchy = kCauchyScalePx / fr.image_scale;
  std::vector<Params> starts = focal_sweep_starts(norm, half_width_norm);
  if (n >= 6 && !result.coplanar)
    if (auto d = dlt_start(norm, CameraModel::kF)) starts.push_back(*d);
  if (starts.empty()) throw InputError("", "no camera explains these points (PnP found no pose at any focal length)");
  FitOutcome best;
  best.cost = std::numeric_limits<double>::infinity();
  for (const Params& s : starts) {
    const FitOutcome f = refine(s, CameraModel::kF, norm, cauchy);
    if (f.converged && f.params.intr[0] > 0 && f.cost < best.cost) best = f;
  }
  if (!std::isfinite(best.cost)) throw InputError("", "the fit did not converge from any start");

  // 2. Outliers, one at a time: the worst residual of the robust fit, if it lies beyond 5 robust σ
  // (σ from the median residual length of the remaining points, which is 1.1774σ for 2-D Gaussian
  // errors, corrected for the degrees of freedom the fit used) and beyond 3 px, is left out and the robust fit repeated; this stops while the
  // remaining points still over-determine model f by at least two residuals.
  // The search uses the richest model the points can afford (a poorer one would call its own
  // systematic error an outlier): the requested model, else f+c+a for eight or more
  // non-coplanar points, else f.
  const CameraModel search_model = options.model ? *options.model
                                   : (n >= 8 && !result.coplanar) ? CameraModel::kFCA : CameraModel::kF;
  if (search_model != CameraModel::kF) {
    const FitOutcome rich = refine(best.params, search_model, norm, cauchy);
    if (rich.converged && rich.params.intr[0] > 0) best = rich;
  }
  std::vector<bool> outlier(static_cast<std::size_t>(n), false);
  int kept = n;
  std::vector<std::string> outlier_names;
  double threshold = kOutlierMinPx;
  for (;;) {
    std::vector<double> r_px(static_cast<std::size_t>(n)), kept_r;
    for (int i = 0; i < n; ++i) {
      const NormPoint& q = norm[std::size_t(i)];
      r_px[std::size_t(i)] = (project_norm(best.params, q.p) - q.uv).norm() * fr.image_scale;
      if (!outlier[std::size_t(i)]) kept_r.push_back(r_px[std::size_t(i)]);
    }
    std::nth_element(kept_r.begin(), kept_r.begin() + long(kept_r.size() / 2), kept_r.end());
    // Fitted residuals are shorter than the errors by sqrt((m − k)/m); undo that for σ.
    const double m_kept = 2.0 * kept, k_search = model_parameter_count(search_model);
    const double dof_factor = m_kept > k_search ? std::sqrt(m_kept / (m_kept - k_search)) : 1.0;
    threshold = std::max(kOutlierMinPx, 5.0 * dof_factor * kept_r[kept_r.size() / 2] / 1.1774);
    int worst = -1;
    for (int i = 0; i < n; ++i)
      if (!outlier[std::size_t(i)] && r_px[std::size_t(i)] > threshold && (worst < 0 || r_px[std::size_t(i)] > r_px[std::size_t(worst)]))
        worst = i;
    if (worst < 0 || 2 * (kept - 1) - model_parameter_count(search_model) < 2) break;
    outlier[std::size_t(worst)] = true;
    --kept;
    outlier_names.push_back(fmt::format("{} ({:.1f} px)", points[std::size_t(worst)].name, r_px[std::size_t(worst)]));
    std::vector<NormPoint> remaining;
    for (int i = 0; i < n; ++i)
      if (!outlier[std::size_t(i)]) remaining.push_back(norm[std::size_t(i)]);
    const FitOutcome again = refine(best.params, search_model, remaining, cauchy);
    if (again.converged) best = again;
  }
  if (!outlier_names.empty())
    result.warnings.push_back(fmt::format("outlier(s) left out of the fit: {} (threshold {:.1f} px)", join_names(outlier_names), threshold));
  std::vector<NormPoint> inl;
  for (int i = 0; i < n; ++i)
    if (!outlier[std::size_t(i)]) inl.push_back(norm[std::size_t(i)]);
  const int m = 2 * kept;

  // 3. Plain least squares on the inliers, for each model the points can support.
  const std::optional<Params> dlt_full = (kept >= 6 && !result.coplanar) ? dlt_start(inl, CameraModel::kFCA) : std::nullopt;
  std::vector<Params> fitted(3);
  const FitOutcome f_fit = refine(best.params, CameraModel::kF, inl, 0);
  fitted[0] = f_fit.params;
  for (CameraModel model : {CameraModel::kF, CameraModel::kFC, CameraModel::kFCA}) {
    ModelFit mf;
    mf.model = model;
    mf.residuals = m;
    const int k = model_parameter_count(model);
    const bool wanted = options.model ? *options.model == model : true;
    if (!wanted && options.model) { mf.note = "not requested"; result.fits.push_back(mf); continue; }
    if (m - k < (options.model ? 0 : 1)) { mf.note = fmt::format("needs more than {} points", (k + 1) / 2); result.fits.push_back(mf); continue; }
    if (!options.model && model != CameraModel::kF && result.coplanar) { mf.note = "coplanar points"; result.fits.push_back(mf); continue; }
    const int idx = int(model);
    if (model != CameraModel::kF) {
      FitOutcome a = refine(f_fit.params, model, inl, 0);
      if (dlt_full) {
        const FitOutcome b = refine(*dlt_full, model, inl, 0);
        if (b.converged && (!a.converged || b.cost < a.cost)) a = b;
      }
      fitted[std::size_t(idx)] = a.params;
    }
    mf.fitted = true;
    mf.rss_px2 = rss_norm(fitted[std::size_t(idx)], inl) * fr.image_scale * fr.image_scale;
    mf.rms_px = std::sqrt(mf.rss_px2 / m);
    result.fits.push_back(mf);
  }

  // 4. The model: as requested, or the F-test chain f -> f+c -> f+c+a.
  CameraModel chosen = options.model.value_or(CameraModel::kF);
  if (options.model) {
    result.selection = "requested";
  } else {
    result.selection = "auto: f";
    for (CameraModel richer : {CameraModel::kFC, CameraModel::kFCA}) {
      ModelFit& cur = result.fits[std::size_t(int(chosen))];
      ModelFit& alt = result.fits[std::size_t(int(richer))];
      if (!alt.fitted) continue;
      const int k1 = model_parameter_count(chosen), k2 = model_parameter_count(richer);
      if (cur.rms_px < kExactFitPx) {
        alt.note = fmt::format("not needed: {} fits exactly", model_name(chosen));
        continue;
      }
      const double F = ((cur.rss_px2 - alt.rss_px2) / (k2 - k1)) / (alt.rss_px2 / (m - k2));
      alt.p_value = f_distribution_sf(F, k2 - k1, m - k2);
      alt.note = fmt::format("F({}, {}) = {:.3g} against {}, p = {:.3g}", k2 - k1, m - k2, F, model_name(chosen), alt.p_value);
      if (alt.p_value < options.significance) {
        chosen = richer;
        result.selection = fmt::format("auto: {} (F-test p = {:.2g} < {})", model_name(richer), alt.p_value, options.significance);
      }
    }
    if (chosen == CameraModel::kF) result.selection += fmt::format(" (no richer model improves the fit beyond noise at α = {})", options.significance);
  }
  result.model = chosen;
  const Params& P = fitted[std::size_t(int(chosen))];
  result.camera = to_camera(P, fr, width, height);
  const ModelFit& fit = result.fits[std::size_t(int(chosen))];
  result.rms_px = fit.rms_px;
  result.inliers = kept;
  const int k = model_parameter_count(chosen);
  result.sigma_px = m > k ? std::sqrt(fit.rss_px2 / (m - k)) : 0;

  // Per-point report.
  std::vector<std::string> behind;
  for (int i = 0; i < n; ++i) {
    PointResidual pr;
    pr.name = points[std::size_t(i)].name;
    pr.uv_px = points[std::size_t(i)].uv_px;
    double depth = 0;
    pr.residual_px = result.camera.project(points[std::size_t(i)].p_world, &depth) - pr.uv_px;
    pr.outlier = outlier[std::size_t(i)];
    pr.behind = !(depth > 0);
    if (pr.behind) behind.push_back(pr.name);
    result.points.push_back(pr);
  }
  if (!behind.empty()) result.warnings.push_back("point(s) behind the camera: " + join_names(behind));
  const double hfov = result.camera.hfov_deg();
  if (hfov < 1.0 || hfov > 150.0)
    result.warnings.push_back(fmt::format("implausible horizontal field of view {:.3g}° (focal length {:.4g} px)", hfov, result.camera.fx));

  // 5. Uncertainty: Ceres's covariance (JᵀJ)⁻¹ in the tangent space, scaled by σ̂² = RSS/(m − k),
  // propagated to derived quantities by central differences.
  result.insertion_world = options.insertion_world.value_or(Vec3d(fr.world_centre.x(), 0.0, fr.world_centre.z()));
  result.insertion_px = result.camera.project(result.insertion_world);
  if (m > k && fit.rss_px2 > 0) {
    Params Pc = P;
    ceres::Problem problem;
    for (const auto& q : inl) problem.AddResidualBlock(ReprojectionCost::Create(q.uv, q.p), nullptr, Pc.aa, Pc.t, Pc.intr);
    if (chosen == CameraModel::kF) problem.SetManifold(Pc.intr, new ceres::SubsetManifold(4, {1, 2, 3}));
    else if (chosen == CameraModel::kFC) problem.SetManifold(Pc.intr, new ceres::SubsetManifold(4, {3}));
    ceres::Covariance::Options co;
    co.algorithm_type = ceres::DENSE_SVD;
    ceres::Covariance covariance(co);
    const std::vector<const double*> blocks = {Pc.aa, Pc.t, Pc.intr};
    std::vector<std::pair<const double*, const double*>> pairs;
    for (std::size_t a = 0; a < 3; ++a)
      for (std::size_t b = a; b < 3; ++b) pairs.push_back({blocks[a], blocks[b]});
    Eigen::Matrix<double, 10, 10, Eigen::RowMajor> C;
    if (covariance.Compute(pairs, &problem) && covariance.GetCovarianceMatrix(blocks, C.data())) {
      const double var_norm = fit.rss_px2 / (fr.image_scale * fr.image_scale) / (m - k);
      C *= var_norm;
      // g(θ): fx, fy, cx, cy, aspect, eye (3), hfov, forward (3), up (3), insertion (u, v).
      auto g = [&](const Params& q) {
        const Camera c = to_camera(q, fr, width, height);
        Eigen::Matrix<double, 18, 1> out;
        const Vec3d eye = c.eye_world(), fwd = c.forward_world(), up = c.up_world();
        const Vec2d ins = c.project(result.insertion_world);
        out << c.fx, c.fy, c.cx, c.cy, c.fy / c.fx, eye, c.hfov_deg(), fwd, up, ins;
        return out;
      };
      Eigen::Matrix<double, 18, 10> Jg;
      for (int j = 0; j < 10; ++j) {
        Params plus = P, minus = P;
        double* vp = j < 3 ? &plus.aa[j] : j < 6 ? &plus.t[j - 3] : &plus.intr[j - 6];
        double* vm = j < 3 ? &minus.aa[j] : j < 6 ? &minus.t[j - 3] : &minus.intr[j - 6];
        const double h = 1e-6 * std::max(1.0, std::abs(*vp));
        *vp += h;
        *vm -= h;
        Jg.col(j) = (g(plus) - g(minus)) / (2 * h);
      }
      const Eigen::Matrix<double, 18, 18> G = Jg * C * Jg.transpose();
      auto sd = [&](int i) { return std::sqrt(std::max(0.0, G(i, i))); };
      CalibrationUncertainty& s = result.sigma;
      s.known = true;
      s.fx_px = sd(0); s.fy_px = sd(1); s.cx_px = sd(2); s.cy_px = sd(3); s.aspect = sd(4);
      s.eye_world = Vec3d(sd(5), sd(6), sd(7));
      s.hfov_deg = sd(8);
      // Angular spread of a unit vector: sqrt(trace of its covariance), in degrees.
      s.view_direction_deg = rad_to_deg(std::sqrt(std::max(0.0, G.block<3, 3>(9, 9).trace())));
      s.roll_deg = rad_to_deg(std::sqrt(std::max(0.0, G.block<3, 3>(12, 12).trace())));
      const Eigen::Matrix2d Ci = G.block<2, 2>(15, 15);
      const double lmax = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(Ci).eigenvalues().maxCoeff();
      result.insertion_sigma_px = std::sqrt(std::max(0.0, lmax));
      result.insertion_radius95_px = std::sqrt(std::max(0.0, 5.991 * lmax));  // χ²₂(0.95) = 5.991
    } else {
      result.warnings.push_back("the covariance is singular: the points do not determine every parameter of model " +
                                std::string(model_name(chosen)));
    }
  } else if (m <= k) {
    result.warnings.push_back(fmt::format("{} points exactly determine model {}: no redundancy, so no uncertainty estimate",
                                          kept, model_name(chosen)));
  }
  return result;
}

nlohmann::json calibration_to_json(const CalibrationResult& r) {
  using nlohmann::json;
  json cam = camera_to_json(r.camera);
  json pts = json::array();
  for (const auto& p : r.points)
    pts.push_back({{"name", p.name}, {"uv", {p.uv_px.x(), p.uv_px.y()}}, {"residual_px", {p.residual_px.x(), p.residual_px.y()}},
                   {"outlier", p.outlier}, {"behind", p.behind}});
  json fits = json::array();
  for (const auto& f : r.fits) {
    json j = {{"model", model_name(f.model)}, {"fitted", f.fitted}, {"note", f.note}};
    if (f.fitted) { j["rms_px"] = f.rms_px; j["rss_px2"] = f.rss_px2; }
    if (f.p_value >= 0) j["p_value"] = f.p_value;
    fits.push_back(j);
  }
  json sigma = nullptr;
  if (r.sigma.known) {
    const auto& s = r.sigma;
    sigma = {{"fx_px", s.fx_px}, {"fy_px", s.fy_px}, {"cx_px", s.cx_px}, {"cy_px", s.cy_px}, {"aspect", s.aspect},
             {"eye", {s.eye_world.x(), s.eye_world.y(), s.eye_world.z()}}, {"hfov_deg", s.hfov_deg},
             {"view_direction_deg", s.view_direction_deg}, {"roll_deg", s.roll_deg}};
  }
  cam["calibration"] = {
      {"model", model_name(r.model)},
      {"selection", r.selection},
      {"rms_px", r.rms_px},
      {"sigma_px", r.sigma_px},
      {"inliers", r.inliers},
      {"coplanar", r.coplanar},
      {"points", pts},
      {"fits", fits},
      {"stddev", sigma},
      {"insertion", {{"world", {r.insertion_world.x(), r.insertion_world.y(), r.insertion_world.z()}},
                     {"uv", {r.insertion_px.x(), r.insertion_px.y()}},
                     {"sigma_px", r.insertion_sigma_px},
                     {"radius95_px", r.insertion_radius95_px}}},
      {"warnings", r.warnings},
  };
  return cam;
}

std::string calibration_report(const CalibrationResult& r) {
  const Camera& c = r.camera;
  const auto& s = r.sigma;
  std::string out;
  auto pm = [&](double v, double sd, const char* fmtv) {
    return s.known ? fmt::format(fmt::runtime(std::string(fmtv) + " ± " + fmtv), v, sd) : fmt::format(fmt::runtime(fmtv), v);
  };
  out += fmt::format("model        {}  ({})\n", model_name(r.model), r.selection);
  for (const auto& f : r.fits)
    out += f.fitted ? fmt::format("  {:<6} RMS {:.4g} px{}{}\n", model_name(f.model), f.rms_px, f.note.empty() ? "" : "; ", f.note)
                    : fmt::format("  {:<6} not fitted: {}\n", model_name(f.model), f.note);
  // A parameter the model does not fit is fixed, not known to ±0: say so, and why.
  const std::string why = r.selection == "requested" ? "by the requested model" : "not supported by the points";
  if (r.model == CameraModel::kFCA)
    out += fmt::format("fx, fy       {} px, {} px\n", pm(c.fx, s.fx_px, "{:.2f}"), pm(c.fy, s.fy_px, "{:.2f}"));
  else
    out += fmt::format("fx, fy       {} px, fy = fx (square pixels: fixed, {})\n", pm(c.fx, s.fx_px, "{:.2f}"), why);
  if (r.model == CameraModel::kF)
    out += fmt::format("cx, cy       {:.2f} px, {:.2f} px (the image centre: fixed, {})\n", c.cx, c.cy, why);
  else
    out += fmt::format("cx, cy       {} px, {} px\n", pm(c.cx, s.cx_px, "{:.2f}"), pm(c.cy, s.cy_px, "{:.2f}"));
  out += fmt::format("fov          {}° horizontal, {:.3f}° vertical\n", pm(c.hfov_deg(), s.hfov_deg, "{:.3f}"), c.vfov_deg());
  const Vec3d eye = c.eye_world(), look = eye + c.forward_world(), up = c.up_world();
  out += fmt::format("eye          ({:.4f}, {:.4f}, {:.4f})", eye.x(), eye.y(), eye.z());
  out += s.known ? fmt::format(" ± ({:.2g}, {:.2g}, {:.2g})\n", s.eye_world.x(), s.eye_world.y(), s.eye_world.z()) : "\n";
  out += fmt::format("look         ({:.4f}, {:.4f}, {:.4f})\n", look.x(), look.y(), look.z());
  out += fmt::format("up           ({:.4f}, {:.4f}, {:.4f})\n", up.x(), up.y(), up.z());
  if (s.known) out += fmt::format("orientation  view direction ± {:.2g}°, roll ± {:.2g}°\n", s.view_direction_deg, s.roll_deg);
  out += fmt::format("residuals    RMS {:.3g} px over {} inlier(s) (σ̂ = {:.3g} px)\n", r.rms_px, r.inliers, r.sigma_px);
  for (const auto& p : r.points)
    out += fmt::format("  {:<14} ({:8.2f}, {:8.2f})  {:7.3f} px{}{}\n", p.name, p.uv_px.x(), p.uv_px.y(), p.residual_px.norm(),
                       p.outlier ? "  OUTLIER" : "", p.behind ? "  BEHIND" : "");
  out += fmt::format("insertion    ({:.3f}, {:.3f}, {:.3f}) m at pixel ({:.1f}, {:.1f})", r.insertion_world.x(),
                     r.insertion_world.y(), r.insertion_world.z(), r.insertion_px.x(), r.insertion_px.y());
  out += s.known ? fmt::format(": moves by {:.2g} px (1σ), up to {:.2g} px (95%)\n", r.insertion_sigma_px, r.insertion_radius95_px) : "\n";
  for (const auto& w : r.warnings) out += "warning: " + w + "\n";
  return out;
}

}  // namespace insitu
