// Inverse lighting's cost functions (relight/inverse_lighting_costs.h): each with its derivatives
// written out equals the automatic derivative of the same formula, residual and Jacobian, at
// points spread over the range the fit visits (a from 0 to 10⁴, coefficients over six decades).
#include <gtest/gtest.h>

#include <ceres/ceres.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "relight/inverse_lighting_costs.h"

namespace insitu {
namespace {

using inverse_lighting_detail::log_residual_cost;
using inverse_lighting_detail::relative_irradiance_cost;
using inverse_lighting_detail::smoothing_cost;

// Residual and Jacobians of both at `params`, equal to 1e-12 relative.
void expect_same(ceres::CostFunction* fast_raw, ceres::CostFunction* slow_raw,
                 const std::vector<std::vector<double>>& params) {
  const std::unique_ptr<ceres::CostFunction> fast(fast_raw), slow(slow_raw);
  ASSERT_EQ(fast->parameter_block_sizes(), slow->parameter_block_sizes());
  std::vector<const double*> p;
  std::vector<std::vector<double>> jf, js;
  std::vector<double*> jf_ptr, js_ptr;
  for (const auto& b : params) {
    p.push_back(b.data());
    jf.emplace_back(b.size()), js.emplace_back(b.size());
  }
  for (std::size_t b = 0; b < params.size(); ++b) jf_ptr.push_back(jf[b].data()), js_ptr.push_back(js[b].data());
  double rf = 0, rs = 0;
  ASSERT_TRUE(fast->Evaluate(p.data(), &rf, jf_ptr.data()));
  ASSERT_TRUE(slow->Evaluate(p.data(), &rs, js_ptr.data()));
  EXPECT_NEAR(rf, rs, 1e-12 * std::max(1.0, std::abs(rs)));
  for (std::size_t b = 0; b < params.size(); ++b)
    for (std::size_t i = 0; i < params[b].size(); ++i)
      EXPECT_NEAR(jf[b][i], js[b][i], 1e-12 * std::max(1.0, std::abs(js[b][i]))) << "block " << b << ", column " << i;
}

// n columns' a (some at 0, the lower bound) and coefficients over six decades.
struct Point {
  std::vector<double> a, coef;
  Point(std::mt19937& rng, int n) {
    std::uniform_real_distribution<double> u(0, 1);
    for (int c = 0; c < n; ++c) {
      a.push_back(u(rng) < 0.2 ? 0.0 : std::pow(10.0, 4 * u(rng)));
      coef.push_back(std::pow(10.0, 6 * u(rng) - 5));
    }
  }
};

TEST(InverseLightingCosts, AnalyticDerivativesEqualTheAutomaticOnes) {
  std::mt19937 rng(7);
  for (const int n : {1, 3, 17, 100}) {
    for (int trial = 0; trial < 5; ++trial) {
      SCOPED_TRACE(testing::Message() << n << " columns, trial " << trial);
      const Point x(rng, n);
      const double log_rho = std::log(0.18 + 0.1 * trial);
      expect_same(log_residual_cost(-1.3, 0.7, x.coef), log_residual_cost(-1.3, 0.7, x.coef, true), {{log_rho}, x.a});
      expect_same(relative_irradiance_cost(2.5, 0.7, x.coef), relative_irradiance_cost(2.5, 0.7, x.coef, true), {x.a});
      std::vector<std::size_t> same;
      for (int c = 0; c < n; c += 2) same.push_back(std::size_t(c));
      expect_same(smoothing_cost(0, same, 0.3, n), smoothing_cost(0, same, 0.3, n, true), {x.a});
    }
  }
}

// E ≤ 0 has no log: the evaluation fails (Ceres rejects the step) instead of giving NaN.
TEST(InverseLightingCosts, NoIrradianceIsAFailedEvaluation) {
  const std::unique_ptr<ceres::CostFunction> cost(log_residual_cost(0.0, 0.0, {0.0}));
  const double log_rho = 0, a = 1;
  const double* p[] = {&log_rho, &a};
  double r = 0;
  EXPECT_FALSE(cost->Evaluate(p, &r, nullptr));
}

}  // namespace
}  // namespace insitu
