// The residuals of inverse lighting's fit (inverse_lighting_solve.h) as Ceres cost functions, each
// with its derivatives written out and, for tests, as the automatic derivative of the same
// formula: the slower, obviously correct version. With a hundred columns (the parts of eleven
// sources) the automatic derivatives of every pixel's residual were most of the fit's time: a
// Jet of 4 carries the hundred derivatives in 25 passes, each over all hundred columns.
#pragma once
#include <vector>

namespace ceres {
class CostFunction;
}

namespace insitu {
namespace inverse_lighting_detail {

// E = E0 + Σ_c a_c coef_c, the irradiance a pixel's model gives.
template <typename T>
T model_irradiance(double e0, const std::vector<double>& coef, const T* a) {
  T e = T(e0);
  for (std::size_t c = 0; c < coef.size(); ++c) e += a[c] * coef[c];
  return e;
}

// r = log P − log ρ + log π − log E, E = E0 + Σ_c a_c coef_c; parameter blocks log ρ (1) and a.
// ∂r/∂log ρ = −1, ∂r/∂a_c = −coef_c / E.
ceres::CostFunction* log_residual_cost(double log_p, double e0, std::vector<double> coef, bool autodiff = false);

// r = 1 − E / T (a pixel of known albedo, T = π P / ρ); parameter block a. ∂r/∂a_c = −coef_c / T.
ceres::CostFunction* relative_irradiance_cost(double target, double e0, std::vector<double> coef,
                                              bool autodiff = false);

// r = w (log(1 + a_c) − 1/|S| Σ_{k ∈ S} log(1 + a_k)), S ∋ c; parameter block a (n columns).
// ∂r/∂a_k = w ([k = c] / (1 + a_c) − [k ∈ S] / (|S| (1 + a_k))).
ceres::CostFunction* smoothing_cost(std::size_t c, std::vector<std::size_t> same, double weight, int n,
                                    bool autodiff = false);

}  // namespace inverse_lighting_detail
}  // namespace insitu
