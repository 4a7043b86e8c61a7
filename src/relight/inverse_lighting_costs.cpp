#include "relight/inverse_lighting_costs.h"

#include <ceres/ceres.h>

#include <cmath>
#include <utility>

#include "core/math.h"

namespace insitu {
namespace inverse_lighting_detail {

namespace {

// The formulas, for Ceres's automatic derivatives.
struct LogResidual {
  double log_p, e0;
  std::vector<double> coef;
  template <typename T>
  bool operator()(T const* const* params, T* r) const {
    r[0] = T(log_p) - params[0][0] + T(std::log(kPi)) - log(model_irradiance(e0, coef, params[1]));
    return true;
  }
};

struct RelativeIrradiance {
  double target, e0;
  std::vector<double> coef;
  template <typename T>
  bool operator()(T const* const* params, T* r) const {
    r[0] = T(1) - model_irradiance(e0, coef, params[0]) / T(target);
    return true;
  }
};

struct Smoothing {
  std::size_t c;
  std::vector<std::size_t> same;
  double weight;
  template <typename T>
  bool operator()(T const* const* params, T* r) const {
    T mean = T(0);
    for (std::size_t k : same) mean += log(T(1) + params[0][k]);
    r[0] = T(weight) * (log(T(1) + params[0][c]) - mean / T(double(same.size())));
    return true;
  }
};

template <typename Functor>
ceres::CostFunction* automatic(Functor f, std::vector<int> blocks) {
  auto* cost = new ceres::DynamicAutoDiffCostFunction<Functor>(new Functor(std::move(f)));
  for (int b : blocks) cost->AddParameterBlock(b);
  cost->SetNumResiduals(1);
  return cost;
}

// One residual with its derivatives written out.
class Analytic : public ceres::CostFunction {
 public:
  explicit Analytic(std::vector<int> blocks) {
    set_num_residuals(1);
    *mutable_parameter_block_sizes() = std::move(blocks);
  }
};

class LogResidualCost final : public Analytic {
 public:
  explicit LogResidualCost(LogResidual f) : Analytic({1, int(f.coef.size())}), f_(std::move(f)) {}
  bool Evaluate(double const* const* params, double* r, double** jacobians) const override {
    const double e = model_irradiance(f_.e0, f_.coef, params[1]);
    if (!(e > 0)) return false;
    r[0] = f_.log_p - params[0][0] + std::log(kPi) - std::log(e);
    if (jacobians && jacobians[0]) jacobians[0][0] = -1;
    if (jacobians && jacobians[1])
      for (std::size_t c = 0; c < f_.coef.size(); ++c) jacobians[1][c] = -f_.coef[c] / e;
    return true;
  }

 private:
  LogResidual f_;
};

class RelativeIrradianceCost final : public Analytic {
 public:
  explicit RelativeIrradianceCost(RelativeIrradiance f) : Analytic({int(f.coef.size())}), f_(std::move(f)) {}
  bool Evaluate(double const* const* params, double* r, double** jacobians) const override {
    r[0] = 1 - model_irradiance(f_.e0, f_.coef, params[0]) / f_.target;
    if (jacobians && jacobians[0])
      for (std::size_t c = 0; c < f_.coef.size(); ++c) jacobians[0][c] = -f_.coef[c] / f_.target;
    return true;
  }

 private:
  RelativeIrradiance f_;
};

class SmoothingCost final : public Analytic {
 public:
  SmoothingCost(Smoothing f, int n) : Analytic({n}), f_(std::move(f)), n_(n) {}
  bool Evaluate(double const* const* params, double* r, double** jacobians) const override {
    const double* a = params[0];
    const double share = 1.0 / double(f_.same.size());
    double mean = 0;
    for (std::size_t k : f_.same) mean += std::log1p(a[k]);
    r[0] = f_.weight * (std::log1p(a[f_.c]) - share * mean);
    if (!(jacobians && jacobians[0])) return true;
    double* j = jacobians[0];
    std::fill(j, j + n_, 0.0);
    for (std::size_t k : f_.same) j[k] -= f_.weight * share / (1 + a[k]);
    j[f_.c] += f_.weight / (1 + a[f_.c]);
    return true;
  }

 private:
  Smoothing f_;
  int n_;
};

}  // namespace

ceres::CostFunction* log_residual_cost(double log_p, double e0, std::vector<double> coef, bool autodiff) {
  const int n = int(coef.size());
  LogResidual f{log_p, e0, std::move(coef)};
  if (autodiff) return automatic(std::move(f), {1, n});
  return new LogResidualCost(std::move(f));
}

ceres::CostFunction* relative_irradiance_cost(double target, double e0, std::vector<double> coef, bool autodiff) {
  const int n = int(coef.size());
  RelativeIrradiance f{target, e0, std::move(coef)};
  if (autodiff) return automatic(std::move(f), {n});
  return new RelativeIrradianceCost(std::move(f));
}

ceres::CostFunction* smoothing_cost(std::size_t c, std::vector<std::size_t> same, double weight, int n, bool autodiff) {
  Smoothing f{c, std::move(same), weight};
  if (autodiff) return automatic(std::move(f), {n});
  return new SmoothingCost(std::move(f), n);
}

}  // namespace inverse_lighting_detail
}  // namespace insitu
