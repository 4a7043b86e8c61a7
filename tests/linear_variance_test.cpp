// variance_along (relight/linear_variance.h) against the textbook formula σ² gᵀ (JᵀJ)⁻¹ g, its
// independence from the parameters' units, and its null directions.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "relight/linear_variance.h"

namespace insitu {
namespace {

// A random well-conditioned JᵀJ of n parameters (J with 4n rows).
Eigen::MatrixXd random_normal_matrix(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd j(4 * n, n);
  for (int r = 0; r < j.rows(); ++r)
    for (int c = 0; c < n; ++c) j(r, c) = normal(rng);
  return j.transpose() * j;
}

TEST(LinearVariance, IsTheTextbookFormulaForARegularMatrix) {
  const Eigen::MatrixXd jtj = random_normal_matrix(6, 1);
  const Eigen::VectorXd g = Eigen::VectorXd::LinSpaced(6, -1.0, 2.0);
  const double expected = 0.3 * 0.3 * g.dot(jtj.ldlt().solve(g));
  EXPECT_NEAR(variance_along(jtj, g, 0.3), expected, 1e-10 * expected);
}

// Parameters in other units, x = S x' (x_i' = x_i / s_i): J' = J S, J'ᵀJ' = S JᵀJ S, and the same
// combination gᵀx = (S g)ᵀ x', whose variance is unchanged. With one parameter's information 10⁻²⁰ of another's,
// an eigenvalue threshold relative to the largest (the unscaled computation) calls its direction
// null and the variance infinite.
TEST(LinearVariance, DoesNotDependOnTheParametersUnits) {
  const Eigen::MatrixXd jtj = random_normal_matrix(5, 2);
  const Eigen::VectorXd g = Eigen::VectorXd::Ones(5);
  Eigen::VectorXd s(5);
  s << 1e-10, 1.0, 1e3, 1e8, 1.0;
  const Eigen::MatrixXd scaled = s.asDiagonal() * jtj * s.asDiagonal();
  const Eigen::VectorXd g_scaled = s.cwiseProduct(g);
  const double v = variance_along(jtj, g, 1.0), v_scaled = variance_along(scaled, g_scaled, 1.0);
  ASSERT_TRUE(std::isfinite(v_scaled));
  EXPECT_NEAR(v_scaled, v, 1e-6 * v);
}

// A parameter the data say nothing of (a zero row and column): infinite where g weighs it, and
// ignored where it does not; the same for a null direction that is a combination of two.
TEST(LinearVariance, NullDirectionsAreInfiniteOnlyWhereTheCombinationHasThem) {
  Eigen::MatrixXd jtj = Eigen::MatrixXd::Zero(4, 4);
  jtj.topLeftCorner(3, 3) = random_normal_matrix(3, 3);
  EXPECT_TRUE(std::isinf(variance_along(jtj, Eigen::Vector4d(1, 0, 0, 1), 1.0)));
  const double v = variance_along(jtj, Eigen::Vector4d(1, 2, 0, 0), 1.0);
  const Eigen::Vector3d g3(1, 2, 0);
  EXPECT_NEAR(v, g3.dot(jtj.topLeftCorner(3, 3).ldlt().solve(g3)), 1e-9 * v);
  // Two parameters that only their sum is known of: JᵀJ = [[1, 1], [1, 1]].
  const Eigen::Matrix2d sum_only = Eigen::Matrix2d::Ones();
  EXPECT_NEAR(variance_along(sum_only, Eigen::Vector2d(1, 1), 1.0), 1.0, 1e-9);  // (1,1)ᵀ(JᵀJ)⁺(1,1) = 4/2/2
  EXPECT_TRUE(std::isinf(variance_along(sum_only, Eigen::Vector2d(1, -1), 1.0)));
  // No information at all: the zero combination has variance 0, any other is infinite (and an
  // empty eigenproblem is never solved: its largest eigenvalue does not exist).
  const Eigen::Matrix2d none = Eigen::Matrix2d::Zero();
  EXPECT_EQ(variance_along(none, Eigen::Vector2d(0, 0), 1.0), 0.0);
  EXPECT_TRUE(std::isinf(variance_along(none, Eigen::Vector2d(0, 1), 1.0)));
}

}  // namespace
}  // namespace insitu
