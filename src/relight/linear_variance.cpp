#include "relight/linear_variance.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <vector>

namespace insitu {

double variance_along(const Eigen::MatrixXd& jtj, const Eigen::VectorXd& g, double sigma_r) {
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < jtj.rows(); ++i) {
    if (jtj(i, i) > 0 && std::isfinite(jtj(i, i)))
      kept.push_back(i);  // else null: no information (or not a number)
    else if (g[i] != 0)
      return INFINITY;
  }
  if (kept.empty()) return 0;  // no parameter has information, and g has no part in any: g = 0
  Eigen::VectorXd d(Eigen::Index(kept.size())), dg(Eigen::Index(kept.size()));
  for (std::size_t i = 0; i < kept.size(); ++i) {
    d[Eigen::Index(i)] = 1 / std::sqrt(jtj(kept[i], kept[i]));
    dg[Eigen::Index(i)] = d[Eigen::Index(i)] * g[kept[i]];
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(d.asDiagonal() * jtj(kept, kept) * d.asDiagonal());
  const double lambda_max = std::max(1e-300, eig.eigenvalues().maxCoeff());
  double var = 0;
  for (Eigen::Index i = 0; i < dg.size(); ++i) {
    const double c = eig.eigenvectors().col(i).dot(dg), lambda = eig.eigenvalues()[i];
    if (lambda <= 1e-14 * lambda_max) {
      if (c * c > 1e-12 * dg.squaredNorm()) return INFINITY;
      continue;
    }
    var += c * c / lambda;
  }
  return sigma_r * sigma_r * var;
}

}  // namespace insitu
