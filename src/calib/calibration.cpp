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
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "calib/f_test.h"
#include "calib/camera_params.h"
#include "calib/fit_state.h"
#include "calib/object_uncertainty.h"
#include "calib/reprojection_cost.h"

namespace insitu {

const char* model_name(CameraModel m) {
  switch (m) {
    case CameraModel::kF:
      return "f";
    case CameraModel::kFC:
      return "f+c";
    default:
      return "f+c+a";
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

using namespace calib_detail;

constexpr double kExactFitPx = 1e-6;    // an RMS below this is a numerically exact fit
constexpr double kCauchyScalePx = 2.0;  // robust loss scale for the outlier search
constexpr double kOutlierMinPx = 3.0;   // never call a residual below this an outlier

// ---- Least squares (Ceres) -------------------------------------------------------------------

struct FitOutcome {
  Params params;
  double cost = 0;  // Ceres's cost: ½ Σ ρ(r²)
  bool converged = false;
};

// The least-squares problem of a model: one reprojection residual per point (Ceres example style:
// ReprojectionCost::Create), with an optional Cauchy loss, and the intrinsics a model does not
// fit held at their constrained values (f: cx = cy = 0, a = 1; f+c: a = 1).
void add_residuals(ceres::Problem& problem, Params& p, CameraModel model, const std::vector<NormPoint>& pts,
                   double cauchy_scale_norm) {
  for (const auto& q : pts) {
    ceres::LossFunction* loss = cauchy_scale_norm > 0 ? new ceres::CauchyLoss(cauchy_scale_norm) : nullptr;
    problem.AddResidualBlock(ReprojectionCost::Create(q.uv, q.p), loss, p.aa, p.t, p.intr);
  }
  if (model == CameraModel::kF)
    problem.SetManifold(p.intr, new ceres::SubsetManifold(4, {1, 2, 3}));
  else if (model == CameraModel::kFC)
    problem.SetManifold(p.intr, new ceres::SubsetManifold(4, {3}));
}

FitOutcome refine(Params start, CameraModel model, const std::vector<NormPoint>& pts, double cauchy_scale_norm) {
  constrain(start, model);
  ceres::Problem problem;
  add_residuals(problem, start, model, pts, cauchy_scale_norm);
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
  if (M.determinant() < 0) {
    P = -P;
    M = -M;
  }
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
    for (int k = 0; k < 3; ++k) {
      p.aa[k] = rvec[k];
      p.t[k] = tvec[k];
    }
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

// ---- The steps of calibrate() ------------------------------------------------------------------

// Inputs no camera can come from: fewer than five points, a non-finite one, or points outside the
// image (the wrong image size or origin).
void check_inputs(const std::vector<ControlPoint>& points, int width, int height) {
  const int n = int(points.size());
  if (n < 5) throw InputError("", fmt::format("{} control point(s): calibration needs at least 5", n));
  if (width < 1 || height < 1) throw InputError("", "image size must be positive");
  for (const auto& p : points)
    if (!p.uv_px.allFinite() || !p.p_world.allFinite())
      throw InputError(p.where, fmt::format("point {} is not finite", p.name));
  std::string outside;
  int n_outside = 0;
  for (const auto& p : points)
    if (p.uv_px.x() < 0 || p.uv_px.y() < 0 || p.uv_px.x() > width || p.uv_px.y() > height)
      outside += (n_outside++ < 5 ? fmt::format("{}{} ({:.1f}, {:.1f})", outside.empty() ? "" : ", ", p.name,
                                                p.uv_px.x(), p.uv_px.y())
                                  : "");
  if (n_outside > 0)
    throw InputError("",
                     fmt::format("{} point(s) outside the {}x{} image: {}{} — is the image size (or the origin) right?",
                                 n_outside, width, height, outside, n_outside > 5 ? ", ..." : ""));
}

// Normalized frames (Hartley's normalization): the image centred and scaled to ±1, the points
// centred on their centroid and scaled to unit RMS distance.
Frames make_frames(const std::vector<ControlPoint>& points, int width, int height) {
  const int n = int(points.size());
  Frames fr;
  fr.image_centre = Vec2d(0.5 * width, 0.5 * height);
  fr.image_scale = 0.5 * std::max(width, height);
  fr.world_centre = Vec3d::Zero();
  for (const auto& p : points) fr.world_centre += p.p_world / n;
  double ms = 0;
  for (const auto& p : points) ms += (p.p_world - fr.world_centre).squaredNorm() / n;
  fr.world_scale = std::sqrt(ms);
  return fr;
}

// Degenerate point sets are refused; coplanar ones noted; repeated points warned of.
void check_geometry(const std::vector<ControlPoint>& points, const Frames& fr, CalibrationResult& result) {
  const int n = int(points.size());
  const Geometry geo = point_geometry(points, fr.world_centre);
  if (!(fr.world_scale > 0) || geo.singular[1] <= 1e-9 * geo.singular[0])
    throw InputError("", "the control points are coincident or collinear: they cannot determine a camera");
  result.coplanar = geo.singular[2] <= 1e-6 * geo.singular[0];
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      if ((points[i].p_world - points[j].p_world).norm() <= 1e-9 * fr.world_scale)
        result.warnings.add("",
                            fmt::format("points {} and {} have the same 3D position", points[i].name, points[j].name));
      else if ((points[i].uv_px - points[j].uv_px).norm() <= 1e-6 * fr.image_scale)
        result.warnings.add(
            "", fmt::format("points {} and {} were clicked at the same pixel", points[i].name, points[j].name));
    }
}

// A requested model needs 2n ≥ k residuals, and a principal point needs non-coplanar points.
void check_requested_model(const CalibrationOptions& options, int n, CalibrationResult& result) {
  if (!options.model) return;
  const int k = model_parameter_count(*options.model);
  if (2 * n - k < 0)
    throw InputError("", fmt::format("{} points cannot determine model {} ({} parameters need at least {} points)", n,
                                     model_name(*options.model), k, (k + 1) / 2));
  if (*options.model != CameraModel::kF && result.coplanar)
    result.warnings.add("", fmt::format("the points are coplanar: one view of a plane cannot separate the principal "
                                        "point from the pose, so model {} is poorly determined",
                                        model_name(*options.model)));
}

// Step 1. Starts (the focal sweep, and the DLT for six or more non-coplanar points), each refined
// with the robust loss under model f; the best is kept.
FitOutcome robust_start(const std::vector<NormPoint>& norm, double half_width_norm, bool coplanar, double cauchy) {
  std::vector<Params> starts = focal_sweep_starts(norm, half_width_norm);
  if (norm.size() >= 6 && !coplanar)
    if (auto d = dlt_start(norm, CameraModel::kF)) starts.push_back(*d);
  if (starts.empty()) throw InputError("", "no camera explains these points (PnP found no pose at any focal length)");
  FitOutcome best;
  best.cost = std::numeric_limits<double>::infinity();
  for (const Params& s : starts) {
    const FitOutcome f = refine(s, CameraModel::kF, norm, cauchy);
    if (f.converged && f.params.intr[0] > 0 && f.cost < best.cost) best = f;
  }
  if (!std::isfinite(best.cost)) throw InputError("", "the fit did not converge from any start");
  return best;
}

struct OutlierSearch {
  std::vector<bool> outlier;
  int kept = 0;
  std::vector<std::string> names;
  double threshold_px = kOutlierMinPx;
};

// Step 2. Outliers, one at a time: the worst residual of the robust fit, if it lies beyond 5 robust
// σ (σ from the median residual length of the remaining points, which is 1.1774σ for 2-D Gaussian
// errors, corrected for the degrees of freedom the fit used) and beyond 3 px, is left out and the
// robust fit repeated; this stops while the remaining points still over-determine the model by at
// least two residuals. `best` is refined in place.
OutlierSearch find_outliers(const std::vector<ControlPoint>& points, const std::vector<NormPoint>& norm,
                            const Frames& fr, CameraModel search_model, double cauchy, FitOutcome& best) {
  const int n = int(points.size());
  OutlierSearch out{std::vector<bool>(std::size_t(n), false), n, {}, kOutlierMinPx};
  for (;;) {
    std::vector<double> r_px(static_cast<std::size_t>(n)), kept_r;
    for (int i = 0; i < n; ++i) {
      const NormPoint& q = norm[std::size_t(i)];
      r_px[std::size_t(i)] = (project_norm(best.params, q.p) - q.uv).norm() * fr.image_scale;
      if (!out.outlier[std::size_t(i)]) kept_r.push_back(r_px[std::size_t(i)]);
    }
    std::nth_element(kept_r.begin(), kept_r.begin() + long(kept_r.size() / 2), kept_r.end());
    // Fitted residuals are shorter than the errors by sqrt((m − k)/m); undo that for σ.
    const double m_kept = 2.0 * out.kept, k_search = model_parameter_count(search_model);
    const double dof_factor = m_kept > k_search ? std::sqrt(m_kept / (m_kept - k_search)) : 1.0;
    out.threshold_px = std::max(kOutlierMinPx, 5.0 * dof_factor * kept_r[kept_r.size() / 2] / 1.1774);
    int worst = -1;
    for (int i = 0; i < n; ++i)
      if (!out.outlier[std::size_t(i)] && r_px[std::size_t(i)] > out.threshold_px &&
          (worst < 0 || r_px[std::size_t(i)] > r_px[std::size_t(worst)]))
        worst = i;
    if (worst < 0 || 2 * (out.kept - 1) - model_parameter_count(search_model) < 2) break;
    out.outlier[std::size_t(worst)] = true;
    --out.kept;
    out.names.push_back(fmt::format("{} ({:.1f} px)", points[std::size_t(worst)].name, r_px[std::size_t(worst)]));
    std::vector<NormPoint> remaining;
    for (int i = 0; i < n; ++i)
      if (!out.outlier[std::size_t(i)]) remaining.push_back(norm[std::size_t(i)]);
    const FitOutcome again = refine(best.params, search_model, remaining, cauchy);
    if (again.converged) best = again;
  }
  return out;
}

// Step 3. Plain least squares on the inliers for each model the points can support, from the
// robust fit and from the DLT; result.fits gets one row per model. Returns the parameters by model.
std::vector<Params> fit_models(const std::vector<NormPoint>& inl, const Params& start,
                               const CalibrationOptions& options, const Frames& fr, CalibrationResult& result) {
  const int kept = int(inl.size()), m = 2 * kept;
  const std::optional<Params> dlt_full =
      (kept >= 6 && !result.coplanar) ? dlt_start(inl, CameraModel::kFCA) : std::nullopt;
  std::vector<Params> fitted(3);
  const FitOutcome f_fit = refine(start, CameraModel::kF, inl, 0);
  fitted[0] = f_fit.params;
  for (CameraModel model : {CameraModel::kF, CameraModel::kFC, CameraModel::kFCA}) {
    ModelFit mf;
    mf.model = model;
    mf.residuals = m;
    const int k = model_parameter_count(model);
    // A requested model is fitted, and the next richer one too, for the model's own error at the
    // objects (object_uncertainty.h); auto fits all three.
    const bool requested = options.model && *options.model == model;
    const bool next_richer = options.model && int(model) == int(*options.model) + 1;
    if (options.model && !requested && !next_richer) {
      mf.note = "not requested";
      result.fits.push_back(mf);
      continue;
    }
    if (m - k < (requested ? 0 : 1)) {
      mf.note = fmt::format("needs more than {} points", (k + 1) / 2);
      result.fits.push_back(mf);
      continue;
    }
    if (!requested && model != CameraModel::kF && result.coplanar) {
      mf.note = "coplanar points";
      result.fits.push_back(mf);
      continue;
    }
    if (next_richer) mf.note = "fitted for the model's own error at the objects";
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
  return fitted;
}

// Step 4. The model: as requested, or the F-test chain f -> f+c -> f+c+a over m residuals.
CameraModel choose_model(const CalibrationOptions& options, int m, CalibrationResult& result) {
  CameraModel chosen = options.model.value_or(CameraModel::kF);
  if (options.model) {
    result.selection = "requested";
    return chosen;
  }
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
    alt.note =
        fmt::format("F({}, {}) = {:.3g} against {}, p = {:.3g}", k2 - k1, m - k2, F, model_name(chosen), alt.p_value);
    if (alt.p_value < options.significance) {
      chosen = richer;
      result.selection =
          fmt::format("auto: {} (F-test p = {:.2g} < {})", model_name(richer), alt.p_value, options.significance);
    }
  }
  if (chosen == CameraModel::kF)
    result.selection += fmt::format(" (no richer model improves the fit beyond noise at α = {})", options.significance);
  return chosen;
}

// Each point's residual under the chosen camera, and the plausibility warnings.
void report_points(const std::vector<ControlPoint>& points, const std::vector<bool>& outlier,
                   CalibrationResult& result) {
  std::vector<std::string> behind;
  for (std::size_t i = 0; i < points.size(); ++i) {
    PointResidual pr;
    pr.name = points[i].name;
    pr.uv_px = points[i].uv_px;
    double depth = 0;
    pr.residual_px = result.camera.project(points[i].p_world, &depth) - pr.uv_px;
    pr.outlier = outlier[i];
    pr.behind = !(depth > 0);
    if (pr.behind) behind.push_back(pr.name);
    result.points.push_back(pr);
  }
  if (!behind.empty()) result.warnings.add("", "point(s) behind the camera: " + join_names(behind));
  const double hfov = result.camera.hfov_deg();
  if (hfov < 1.0 || hfov > 150.0)
    result.warnings.add("", fmt::format("implausible horizontal field of view {:.3g}° (focal length {:.4g} px)", hfov,
                                        result.camera.fx));
}

// g(θ): what the report gives a σ for — fx, fy, cx, cy, aspect, eye (3), hfov, forward (3),
// up (3) — and its Jacobian by central differences. (The insertion point's pixel is an object's
// point: object_uncertainty.h.)
using Derived = Eigen::Matrix<double, 16, 1>;
Derived derived_quantities(const Params& q, const Frames& fr, int width, int height) {
  const Camera c = to_camera(q, fr, width, height);
  Derived out;
  const Vec3d eye = c.eye_world(), fwd = c.forward_world(), up = c.up_world();
  out << c.fx, c.fy, c.cx, c.cy, c.fy / c.fx, eye, c.hfov_deg(), fwd, up;
  return out;
}

Eigen::Matrix<double, 16, 10> derived_jacobian(const Params& P, const Frames& fr, int width, int height) {
  return numeric_jacobian<16>(P, [&](const Params& q) { return derived_quantities(q, fr, width, height); });
}

// The standard deviations of the derived quantities from their covariance G = J C Jᵀ.
void set_sigmas(const Eigen::Matrix<double, 16, 16>& G, CalibrationResult& result) {
  auto sd = [&](int i) { return std::sqrt(std::max(0.0, G(i, i))); };
  CalibrationUncertainty& s = result.sigma;
  s.known = true;
  s.fx_px = sd(0);
  s.fy_px = sd(1);
  s.cx_px = sd(2);
  s.cy_px = sd(3);
  s.aspect = sd(4);
  s.eye_world = Vec3d(sd(5), sd(6), sd(7));
  s.hfov_deg = sd(8);
  // Angular spread of a unit vector: sqrt(trace of its covariance), in degrees.
  s.view_direction_deg = rad_to_deg(std::sqrt(std::max(0.0, G.block<3, 3>(9, 9).trace())));
  s.roll_deg = rad_to_deg(std::sqrt(std::max(0.0, G.block<3, 3>(12, 12).trace())));
}

// Step 5. Uncertainty: the chosen model's covariance (model_covariance), propagated to the derived
// quantities by their Jacobian; kept in `state` with the next richer model's for object_uncertainty.h.
void estimate_uncertainty(const std::vector<Params>& fitted, CameraModel chosen, const std::vector<NormPoint>& inl,
                          const Frames& fr, int width, int height, CalibrationResult& result,
                          CalibrationFitState& state) {
  const int m = 2 * int(inl.size()), k = model_parameter_count(chosen), idx = int(chosen);
  if (idx + 1 < 3) {
    const ModelFit& next = result.fits[std::size_t(idx + 1)];
    if (next.fitted) state.richer = model_covariance(fitted[std::size_t(idx + 1)], next.model, inl, next.rss_px2, fr);
    state.richer_note = state.richer  ? ""
                        : next.fitted ? std::string(model_name(next.model)) + "'s covariance is singular"
                                      : std::string(model_name(next.model)) + " not fitted: " + next.note;
  } else {
    state.richer_note = "f+c+a is the richest model";
  }
  if (m <= k) {
    result.warnings.add(
        "", fmt::format("{} points exactly determine model {}: no redundancy, so no uncertainty estimate", inl.size(),
                        model_name(chosen)));
    return;
  }
  const double rss_px2 = result.fits[std::size_t(idx)].rss_px2;
  if (!(rss_px2 > 0)) return;
  state.chosen = model_covariance(fitted[std::size_t(idx)], chosen, inl, rss_px2, fr);
  if (!state.chosen) {
    result.warnings.add("", "the covariance is singular: the points do not determine every parameter of model " +
                                std::string(model_name(chosen)));
    return;
  }
  const Eigen::Matrix<double, 16, 10> Jg = derived_jacobian(fitted[std::size_t(idx)], fr, width, height);
  set_sigmas(Jg * state.chosen->C * Jg.transpose(), result);
}

// Where the inliers lie: the convex hull of their pixels and their range of depths.
void set_click_span(const std::vector<ControlPoint>& points, const std::vector<bool>& outlier, const Camera& camera,
                    CalibrationFitState& state) {
  std::vector<cv::Point2f> clicks, hull;
  state.click_depth_min = std::numeric_limits<double>::infinity();
  state.click_depth_max = -state.click_depth_min;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (outlier[i]) continue;
    double depth = 0;
    camera.project(points[i].p_world, &depth);
    state.click_depth_min = std::min(state.click_depth_min, depth);
    state.click_depth_max = std::max(state.click_depth_max, depth);
    clicks.emplace_back(float(points[i].uv_px.x()), float(points[i].uv_px.y()));
  }
  cv::convexHull(clicks, hull);
  if (hull.size() >= 3)
    for (const auto& p : hull) state.clicks_hull_px.emplace_back(p.x, p.y);
}

}  // namespace

std::optional<ModelCovariance> model_covariance(const Params& params, CameraModel model,
                                                const std::vector<NormPoint>& inliers, double rss_px2,
                                                const Frames& fr) {
  const int m = 2 * int(inliers.size()), k = model_parameter_count(model);
  if (m <= k || !(rss_px2 > 0)) return std::nullopt;
  Params Pc = params;
  ceres::Problem problem;
  add_residuals(problem, Pc, model, inliers, 0);
  ceres::Covariance::Options co;
  co.algorithm_type = ceres::DENSE_SVD;
  ceres::Covariance covariance(co);
  const std::vector<const double*> blocks = {Pc.aa, Pc.t, Pc.intr};
  std::vector<std::pair<const double*, const double*>> pairs;
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t b = a; b < 3; ++b) pairs.push_back({blocks[a], blocks[b]});
  Eigen::Matrix<double, 10, 10, Eigen::RowMajor> C;
  if (!covariance.Compute(pairs, &problem) || !covariance.GetCovarianceMatrix(blocks, C.data())) return std::nullopt;
  ModelCovariance out;
  out.model = model;
  out.params = params;
  const double var_norm = rss_px2 / (fr.image_scale * fr.image_scale) / (m - k);
  out.C = C * var_norm;
  out.sigma_norm = std::sqrt(var_norm);
  return out;
}

CalibrationResult calibrate(const std::vector<ControlPoint>& points, int width, int height,
                            const CalibrationOptions& options) {
  check_inputs(points, width, height);
  const int n = int(points.size());
  CalibrationResult result;
  const Frames fr = make_frames(points, width, height);
  check_geometry(points, fr, result);
  check_requested_model(options, n, result);
  std::vector<NormPoint> norm;
  for (const auto& p : points) norm.push_back({fr.to_norm(p.uv_px), fr.to_norm(p.p_world)});

  const double cauchy = kCauchyScalePx / fr.image_scale;
  FitOutcome best = robust_start(norm, 0.5 * width / fr.image_scale, result.coplanar, cauchy);
  // The outlier search uses the richest model the points can afford (a poorer one would call its
  // own systematic error an outlier): the requested model, else f+c+a for eight or more
  // non-coplanar points, else f.
  const CameraModel search_model = options.model                  ? *options.model
                                   : (n >= 8 && !result.coplanar) ? CameraModel::kFCA
                                                                  : CameraModel::kF;
  if (search_model != CameraModel::kF) {
    const FitOutcome rich = refine(best.params, search_model, norm, cauchy);
    if (rich.converged && rich.params.intr[0] > 0) best = rich;
  }
  const OutlierSearch outliers = find_outliers(points, norm, fr, search_model, cauchy, best);
  if (!outliers.names.empty())
    result.warnings.add("", fmt::format("outlier(s) left out of the fit: {} (threshold {:.1f} px)",
                                        join_names(outliers.names), outliers.threshold_px));
  std::vector<NormPoint> inl;
  for (int i = 0; i < n; ++i)
    if (!outliers.outlier[std::size_t(i)]) inl.push_back(norm[std::size_t(i)]);

  const std::vector<Params> fitted = fit_models(inl, best.params, options, fr, result);
  const int m = 2 * outliers.kept;
  const CameraModel chosen = choose_model(options, m, result);
  result.model = chosen;
  const Params& P = fitted[std::size_t(int(chosen))];
  result.camera = to_camera(P, fr, width, height);
  const ModelFit& fit = result.fits[std::size_t(int(chosen))];
  result.rms_px = fit.rms_px;
  result.inliers = outliers.kept;
  const int k = model_parameter_count(chosen);
  result.sigma_px = m > k ? std::sqrt(fit.rss_px2 / (m - k)) : 0;
  report_points(points, outliers.outlier, result);

  result.insertion_world = options.insertion_world.value_or(Vec3d(fr.world_centre.x(), 0.0, fr.world_centre.z()));
  result.insertion_px = result.camera.project(result.insertion_world);
  auto state = std::make_shared<CalibrationFitState>();
  state->frames = fr;
  set_click_span(points, outliers.outlier, result.camera, *state);
  estimate_uncertainty(fitted, chosen, inl, fr, width, height, result, *state);
  result.state = std::move(state);
  // One figure at the insertion point, the one the objects' corners get (object_uncertainty.h).
  const PointUncertainty at =
      object_uncertainty(result, "insertion", {{"insertion", result.insertion_world}}).points.at(0);
  if (result.sigma.known) {
    result.insertion_sigma_px = at.noise_sigma_px;
    result.insertion_noise_radius95_px = at.noise_radius95_px;
    result.insertion_radius95_px = at.radius95_px;
    result.insertion_model_shift_px = at.model_shift_px;
  }
  return result;
}

}  // namespace insitu
