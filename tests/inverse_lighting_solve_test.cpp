// The smoothing within a source of inverse lighting's fit with a reference
// (relight/inverse_lighting_solve.h, kReferenceSmoothing), on synthetic pixels whose irradiance is
// given: a grey reference of albedo 0.18 lit by E0 and two parts of one source, P = ρ/π (E0 +
// a_1 E_1 + a_2 E_2) with ±2 % noise in log P.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <atomic>
#include <cmath>
#include <vector>

#include "core/colour.h"
#include "core/stop.h"
#include "relight/inverse_lighting_solve.h"

namespace insitu {
namespace {

using inverse_lighting_detail::Albedos;
using inverse_lighting_detail::Columns;
using inverse_lighting_detail::Fit;
using inverse_lighting_detail::FitPixel;

constexpr double kRho = 0.18;

// Surface 0: a reference of known albedo kRho. `e1`, `e2`: each part's irradiance per unit of a.
std::vector<FitPixel> reference_pixels(const std::vector<double>& e1, const std::vector<double>& e2, double a1,
                                       double a2) {
  std::vector<FitPixel> px;
  for (std::size_t i = 0; i < e1.size(); ++i) {
    FitPixel p;
    p.surface = 0;
    p.e0 = 1.0 + e1[i] + e2[i];  // the rest of the cube, and the parts at their lower bound
    p.ek = {e1[i], e2[i]};
    const double noise = 0.02 * std::sin(7.3 * double(i) + 1.1);  // ±2 %, deterministic
    p.log_p = std::log(kRho / kPi * (p.e0 + a1 * e1[i] + a2 * e2[i])) + noise;
    px.push_back(p);
  }
  return px;
}

Albedos reference_albedos() {
  Albedos a;
  a.log_rho = {std::log(kRho)};
  a.known = {true};
  a.mean = {std::nullopt};
  a.reference = {true};
  a.surfaces = a.references = 1;
  return a;
}

// Two parts a degree apart, as a matt ball sees them: their irradiance differs by 0.5 % from pixel
// to pixel; truth a = 20 and 20.
std::vector<FitPixel> parts_a_degree_apart() {
  std::vector<double> e1, e2;
  for (int i = 0; i < 400; ++i) {
    const double cos_theta = 0.05 + 0.95 * (i + 0.5) / 400;  // over the ball's lit side
    e1.push_back(0.01 * cos_theta);
    e2.push_back(0.01 * cos_theta * (1 + 0.005 * std::cos(0.1 * i)));
  }
  return reference_pixels(e1, e2, 20, 20);
}

// σ of a_1 − a_2 from the fit's JᵀJ (the data's alone) and its residuals' scale.
double sigma_of_difference(const Fit& fit) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(fit.jtj.rows());
  g[0] = 1, g[1] = -1;
  const Eigen::MatrixXd cov = fit.jtj.completeOrthogonalDecomposition().pseudoInverse();
  return std::sqrt(std::max(0.0, double(g.transpose() * cov * g))) * std::max(fit.sigma_r, 1e-12);
}

// A stop (core/stop.h) ends the solver at its next iteration, and the fit throws Stopped rather
// than return the scales it had reached.
TEST(InverseLightingSolve, AStopEndsTheFit) {
  const std::vector<FitPixel> px = parts_a_degree_apart();
  const std::vector<int> source{0, 0};
  const std::atomic<bool> stop{true};
  EXPECT_THROW(inverse_lighting_detail::solve(px, Columns{{0}, {1}}, reference_albedos(), &stop, nullptr, &source),
               Stopped);
  EXPECT_THROW(inverse_lighting_detail::solve(px, Columns{{0}, {1}}, reference_albedos(), &stop), Stopped);
}

// Two parts a degree apart under 2 % noise. The photo gives their sum (truth a = 20 + 20) but not
// their split: the free fit gives 17 and 23. The smoothing gives both the same scale and leaves the
// sum to the data; JᵀJ, and so the σ that judges whether a part is determined, are the data's
// alone, the same as without the smoothing.
TEST(InverseLightingSolve, ASourcesPartsThePhotoCannotTellApartShareItsScale) {
  const std::vector<FitPixel> px = parts_a_degree_apart();
  const Columns columns{{0}, {1}};
  const std::vector<int> source{0, 0};
  const Fit smooth = inverse_lighting_detail::solve(px, columns, reference_albedos(), nullptr, nullptr, &source);
  const Fit free = inverse_lighting_detail::solve(px, columns, reference_albedos(), nullptr);
  ASSERT_TRUE(smooth.referenced);
  EXPECT_NEAR(std::log1p(smooth.a[0]), std::log1p(smooth.a[1]), 0.05) << smooth.a[0] << ", " << smooth.a[1];
  // The sum is the data's: within the σ of the free fit's sum, which the data determine.
  EXPECT_NEAR(smooth.a[0] + smooth.a[1], 40, 0.1 * 40);
  EXPECT_NEAR(smooth.a[0] + smooth.a[1], free.a[0] + free.a[1], 0.05 * 40);
  // The data alone leave the split unknown, with or without the smoothing.
  EXPECT_GT(sigma_of_difference(smooth), 40.0);
  ASSERT_EQ(smooth.jtj.rows(), free.jtj.rows());
  EXPECT_LT((smooth.jtj - free.jtj).norm(), 0.05 * free.jtj.norm());
}

// A sun in a sky, told apart by the data (each part lights its own half of the pixels, and doubles
// the light there): the smoothing must not pull the sun toward the sky. Truth
// a = 1000 and 10; each stays within 1 % of the free fit. (A prior acts where the data are weak:
// with the sun adding 5 % where it shines and the sky 10 %, it took 3 % off the sun's scale and
// added 3 % to the sky's.)
TEST(InverseLightingSolve, PartsTheDataTellApartKeepTheirScales) {
  std::vector<double> e1, e2;
  for (int i = 0; i < 400; ++i) {
    const double cos_theta = 0.05 + 0.95 * (i / 2 + 0.5) / 200;
    e1.push_back(i % 2 ? 1e-3 * cos_theta : 0.0);
    e2.push_back(i % 2 ? 0.0 : 0.1 * cos_theta);
  }
  const std::vector<FitPixel> px = reference_pixels(e1, e2, 1000, 10);
  const std::vector<int> source{0, 0};
  const Fit fit = inverse_lighting_detail::solve(px, Columns{{0}, {1}}, reference_albedos(), nullptr, nullptr, &source);
  const Fit free = inverse_lighting_detail::solve(px, Columns{{0}, {1}}, reference_albedos(), nullptr);
  EXPECT_NEAR(std::log(fit.a[0]), std::log(free.a[0]), 0.01) << fit.a[0] << " against " << free.a[0];
  EXPECT_NEAR(std::log(fit.a[1]), std::log(free.a[1]), 0.01) << fit.a[1] << " against " << free.a[1];
  EXPECT_NEAR(free.a[0], 1000, 0.03 * 1000);
  EXPECT_NEAR(free.a[1], 10, 0.03 * 10);
}

// Without a reference there is no smoothing: the same pixels as a surface of unknown albedo give
// the fit without `column_source`'s.
TEST(InverseLightingSolve, WithoutAReferenceNothingIsSmoothed) {
  const std::vector<FitPixel> px = parts_a_degree_apart();
  Albedos albedos = reference_albedos();
  albedos.reference = {false};
  const std::vector<int> source{0, 0};
  const Fit with = inverse_lighting_detail::solve(px, Columns{{0}, {1}}, albedos, nullptr, nullptr, &source);
  const Fit without = inverse_lighting_detail::solve(px, Columns{{0}, {1}}, albedos, nullptr);
  EXPECT_FALSE(with.referenced);
  EXPECT_EQ(with.a, without.a);
}

}  // namespace
}  // namespace insitu
