#include "relight/inverse_lighting_solve.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "core/colour.h"
#include "core/stop.h"
#include "relight/inverse_lighting_costs.h"

namespace insitu {
namespace inverse_lighting_detail {

namespace {

// coef(p, c) = Σ_{j ∈ c} E_j(p): each column's irradiance at pixel p per unit of its a.
std::vector<double> column_coefficients(const FitPixel& p, const Columns& columns) {
  std::vector<double> coef;
  for (const auto& c : columns) {
    double sum = 0;
    for (int j : c) sum += p.ek[std::size_t(j)];
    coef.push_back(sum);
  }
  return coef;
}

// A pixel's data: log P, E0 and each column's coefficient.
struct PixelModel {
  double log_p, e0;
  std::vector<double> coef;
};

// A surface of known mean albedo ρ̄ (a reference): log(mean_i π P_i / E_i) = log ρ̄, within 1 %.
struct MeanAlbedoResidual {
  std::vector<PixelModel> pixels;
  double log_ref;
  template <typename T>
  bool operator()(T const* const* params, T* r) const {
    T sum = T(0);
    for (const PixelModel& p : pixels)
      sum += exp(T(p.log_p) + T(std::log(kPi)) - log(model_irradiance(p.e0, p.coef, params[0])));
    r[0] = (log(sum / T(double(pixels.size()))) - T(log_ref)) / T(0.01);
    return true;
  }
};

// Robust scale of the residuals: 1.4826 · median |r|.
double robust_sigma(std::vector<double> r) {
  if (r.empty()) return 0;
  for (double& v : r) v = std::abs(v);
  std::nth_element(r.begin(), r.begin() + std::ptrdiff_t(r.size() / 2), r.end());
  return 1.4826 * r[r.size() / 2];
}

// JᵀJ of the robustified `residuals` over `blocks` (their columns in order).
Eigen::MatrixXd normal_matrix(ceres::Problem& problem, const std::vector<double*>& blocks,
                              const std::vector<ceres::ResidualBlockId>& residuals) {
  ceres::Problem::EvaluateOptions eval;
  eval.parameter_blocks = blocks;
  eval.residual_blocks = residuals;
  eval.apply_loss_function = true;
  ceres::CRSMatrix crs;
  problem.Evaluate(eval, nullptr, nullptr, nullptr, &crs);
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r)
    for (int k = crs.rows[std::size_t(r)]; k < crs.rows[std::size_t(r) + 1]; ++k)
      j(r, crs.cols[std::size_t(k)]) = crs.values[std::size_t(k)];
  return j.transpose() * j;
}

// How the log residuals are weighed: the Cauchy loss's scale, and a factor per surface on it
// (empty: 1 each); and the weight λ of the smoothing within a source (0: none).
struct Weights {
  double cauchy = kCauchyScale;
  std::vector<double> surface;
  double smoothing = 0;
};

// r_c = √(λN) (log(1 + a_c) − 1/|S| Σ_{c' ∈ S} log(1 + a_c')), S the columns that are single parts
// of c's source (c among them): the pull of one part's scale toward its source's others
// (smoothing_cost).
// The smoothing's residuals, one per column that is a single part of a source with two or more
// such columns (`column_source`: that source, −1 for any other column).
void add_smoothing(ceres::Problem& problem, const std::vector<int>& column_source, double lambda, std::size_t n,
                   double* a) {
  for (std::size_t c = 0; c < column_source.size(); ++c) {
    if (column_source[c] < 0) continue;
    std::vector<std::size_t> same;
    for (std::size_t d = 0; d < column_source.size(); ++d)
      if (column_source[d] == column_source[c]) same.push_back(d);
    if (same.size() < 2) continue;
    problem.AddResidualBlock(
        smoothing_cost(c, std::move(same), std::sqrt(lambda * double(n)), int(column_source.size())), nullptr, a);
  }
}

// The pixels' residuals and the references' constraints.
void add_residuals(ceres::Problem& problem, const std::vector<FitPixel>& pixels, const Columns& columns,
                   std::vector<double>& log_rho, const Albedos& albedos, const Weights& w, double* a) {
  std::vector<MeanAlbedoResidual> refs(log_rho.size());
  for (const FitPixel& p : pixels) {
    const auto s = std::size_t(p.surface);
    PixelModel model{p.log_p, p.e0, column_coefficients(p, columns)};
    if (albedos.mean[s]) refs[s].pixels.push_back(model);
    ceres::CostFunction* cost = log_residual_cost(model.log_p, model.e0, std::move(model.coef));
    ceres::LossFunction* loss = new ceres::CauchyLoss(w.cauchy);
    if (!w.surface.empty() && w.surface[s] != 1)
      loss = new ceres::ScaledLoss(loss, w.surface[s], ceres::TAKE_OWNERSHIP);
    problem.AddResidualBlock(cost, loss, &log_rho[s], a);
  }
  for (std::size_t s = 0; s < refs.size(); ++s) {
    if (refs[s].pixels.empty()) continue;
    refs[s].log_ref = std::log(*albedos.mean[s]);
    auto* cost = new ceres::DynamicAutoDiffCostFunction<MeanAlbedoResidual>(new MeanAlbedoResidual(std::move(refs[s])));
    cost->AddParameterBlock(int(columns.size()));
    cost->SetNumResiduals(1);
    problem.AddResidualBlock(cost, nullptr, a);
  }
}

// Ends a solve at its next iteration once `stop` is set (Ceres calls it after iteration 0 too).
class StopCallback : public ceres::IterationCallback {
 public:
  explicit StopCallback(const std::atomic<bool>* stop) : stop_(stop) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    return stop_ && stop_->load(std::memory_order_relaxed) ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  const std::atomic<bool>* stop_;
};

// Solves `problem` with every a ≥ 0 (dense QR: at most ~120 unknowns); throws Stopped when
// `stop` ended it.
void solve_with_a_nonnegative(ceres::Problem& problem, std::vector<double>& a, const std::atomic<bool>* stop) {
  for (std::size_t c = 0; c < a.size(); ++c) problem.SetParameterLowerBound(a.data(), int(c), 0.0);
  StopCallback callback(stop);
  ceres::Solver::Options options;
  options.max_num_iterations = 200;
  options.linear_solver_type = ceres::DENSE_QR;
  options.callbacks.push_back(&callback);
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  throw_if_stopped(stop);
}

// One robust least-squares fit from `start` (a = 0 and the initial ρ when null). JᵀJ is the
// data's alone: the smoothing moves the fit along the directions the data leaves nearly flat, and
// must not count as their precision (a σ from it would call a part determined that the photo
// cannot see).
Fit solve_pass(const std::vector<FitPixel>& pixels, const Columns& columns, const Albedos& albedos, const Weights& w,
               const Fit* start, const std::atomic<bool>* stop, const std::vector<int>* column_source = nullptr) {
  Fit fit;
  fit.a = start ? start->a : std::vector<double>(columns.size(), 0.0);
  fit.log_rho = start ? start->log_rho : albedos.log_rho;
  ceres::Problem problem;
  add_residuals(problem, pixels, columns, fit.log_rho, albedos, w, fit.a.data());
  std::vector<ceres::ResidualBlockId> data;
  problem.GetResidualBlocks(&data);
  if (w.smoothing > 0 && column_source)
    add_smoothing(problem, *column_source, w.smoothing, pixels.size(), fit.a.data());
  std::vector<double*> free_blocks{fit.a.data()};
  for (std::size_t s = 0; s < fit.log_rho.size(); ++s) {
    if (!problem.HasParameterBlock(&fit.log_rho[s])) continue;
    if (albedos.known[s])
      problem.SetParameterBlockConstant(&fit.log_rho[s]);
    else
      free_blocks.push_back(&fit.log_rho[s]);
  }
  solve_with_a_nonnegative(problem, fit.a, stop);
  ceres::Problem::EvaluateOptions eval;
  eval.apply_loss_function = false;
  problem.Evaluate(eval, nullptr, &fit.residuals, nullptr, nullptr);
  fit.residuals.resize(pixels.size());  // the pixels' come first, in order
  fit.sigma_r = robust_sigma(fit.residuals);
  fit.jtj = normal_matrix(problem, free_blocks, data);
  return fit;
}

// A reference's weight (σ / σ_ref)²: σ_ref the robust σ of its own log residuals, at least 1 %
// (no photo pixel is known better: 8-bit steps, noise), σ that of all pixels; 1 for the rest.
Weights reference_weights(const std::vector<FitPixel>& pixels, const Fit& fit, const Albedos& albedos) {
  std::vector<std::vector<double>> r(albedos.log_rho.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) r[std::size_t(pixels[i].surface)].push_back(fit.residuals[i]);
  Weights w{kCauchyScale, std::vector<double>(r.size(), 1.0)};
  for (std::size_t s = 0; s < r.size(); ++s)
    if (albedos.reference[s] && r[s].size() >= 8)
      w.surface[s] = std::pow(fit.sigma_r / std::max(0.01, robust_sigma(r[s])), 2);
  return w;
}

// The start of a fit with a reference: the a ≥ 0 that best match the known-albedo pixels' own
// irradiance in plain least squares, linear in a and so a convex problem whose minimum the
// solver finds from anywhere (the log residuals' fit has several basins: from the lower bound,
// the same scene's fit found the ceiling lamps × 17 with the ball in the photo and left them
// undetermined with the ball on a plate).
Fit convex_start(const std::vector<FitPixel>& pixels, const Columns& columns, const Albedos& albedos,
                 const std::atomic<bool>* stop) {
  Fit start;
  start.a.assign(columns.size(), 0.0);
  start.log_rho = albedos.log_rho;
  ceres::Problem problem;
  for (const FitPixel& p : pixels) {
    const auto s = std::size_t(p.surface);
    if (!albedos.known[s]) continue;
    // r = 1 − (E0 + Σ_c a_c coef_c) / T, T = π P / ρ the irradiance a pixel of known albedo shows:
    // linear in a.
    problem.AddResidualBlock(
        relative_irradiance_cost(kPi * std::exp(p.log_p - albedos.log_rho[s]), p.e0, column_coefficients(p, columns)),
        nullptr, start.a.data());
  }
  if (problem.NumResidualBlocks() == 0) return start;
  solve_with_a_nonnegative(problem, start.a, stop);
  return start;
}

// The pixels that tell something of the light where a reference is in the photo: not those of a
// surface of unknown albedo (no reference of its own) whose pixels all see one E (distant light
// over a plane), where ρ E is one number that ρ takes. They would only fit that ρ, and over a
// checkered floor (checks 3.7× apart) their robust fit flipped between the two checks and dragged
// the light with it: with the ball on a plate, the open ground's ceiling lamps went from × 17 to
// undetermined (error 27 %) once the floor's pixels near the ball, half of them light checks,
// entered the fit; without those pixels, × 19 (7.8 %).
std::vector<FitPixel> informative(const std::vector<FitPixel>& pixels, const Albedos& albedos) {
  std::map<int, const FitPixel*> first;
  std::map<int, bool> varies;
  for (const FitPixel& p : pixels) {
    const auto [it, fresh] = first.emplace(p.surface, &p);
    if (!fresh && (p.e0 != it->second->e0 || p.ek != it->second->ek)) varies[p.surface] = true;
  }
  std::vector<FitPixel> out;
  for (const FitPixel& p : pixels) {
    const auto s = std::size_t(p.surface);
    if (albedos.known[s] || albedos.mean[s] || varies[p.surface]) out.push_back(p);
  }
  return out;
}

}  // namespace

Fit solve(const std::vector<FitPixel>& all_pixels, const Columns& columns, const Albedos& albedos,
          const std::atomic<bool>* stop, const std::vector<double>* a_start, const std::vector<int>* column_source) {
  if (std::none_of(all_pixels.begin(), all_pixels.end(),
                   [&](const FitPixel& p) { return albedos.reference[std::size_t(p.surface)]; })) {
    Fit start;
    if (a_start) start.a = *a_start, start.log_rho = albedos.log_rho;
    return solve_pass(all_pixels, columns, albedos, {kCauchyScale, {}}, a_start ? &start : nullptr, stop);
  }
  const std::vector<FitPixel> pixels = informative(all_pixels, albedos);
  const Fit convex = convex_start(pixels, columns, albedos, stop);
  const Fit coarse = solve_pass(pixels, columns, albedos, {1.0, {}, kReferenceSmoothing}, &convex, stop, column_source);
  const Fit first =
      solve_pass(pixels, columns, albedos, {kCauchyScale, {}, kReferenceSmoothing}, &coarse, stop, column_source);
  Weights w = reference_weights(pixels, first, albedos);
  w.smoothing = kReferenceSmoothing;
  Fit fit = solve_pass(pixels, columns, albedos, w, &first, stop, column_source);
  fit.referenced = true;
  return fit;
}

Albedos initial_albedos(const std::vector<FitPixel>& pixels, const InverseLightingInput& in) {
  Albedos a;
  const std::size_t n = in.planes.size() + 6 + 2 * in.references.size();  // and each ball's shadow zone
  a.log_rho.assign(n, 0.0);
  a.known.assign(n, false);
  a.mean.assign(n, std::nullopt);
  a.reference.assign(n, false);
  std::vector<std::vector<double>> ratio(n);
  for (const FitPixel& p : pixels) ratio[std::size_t(p.surface)].push_back(p.log_p - std::log(p.e0) + std::log(kPi));
  for (std::size_t s = 0; s < n; ++s) {
    if (ratio[s].empty()) continue;
    std::nth_element(ratio[s].begin(), ratio[s].begin() + std::ptrdiff_t(ratio[s].size() / 2), ratio[s].end());
    a.log_rho[s] = ratio[s][ratio[s].size() / 2];
    std::optional<float> known;
    if (s < in.planes.size()) known = in.planes[s].albedo;
    if (s >= in.planes.size() + 6 && s < in.planes.size() + 6 + in.references.size())
      known = in.references[s - in.planes.size() - 6].albedo, a.reference[s] = true;
    if (known) {
      a.known[s] = true;
      a.log_rho[s] = std::log(std::max(1e-6f, *known));
    }
    if (s < in.planes.size() && in.planes[s].mean_albedo) a.mean[s] = std::max(1e-6f, *in.planes[s].mean_albedo);
    if (s < in.planes.size() + 6 + in.references.size()) ++a.surfaces;  // a ball's shadow zone is its floor
    a.references += (a.known[s] || a.mean[s]) ? 1 : 0;
  }
  return a;
}

}  // namespace inverse_lighting_detail
}  // namespace insitu
