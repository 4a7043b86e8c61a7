// The F distribution's survival function (calib/f_test.h) against published table values.
#include <gtest/gtest.h>

#include <ceres/gradient_checker.h>

#include <random>

#include "calib/calibration.h"
#include "core/error.h"
#include "calib/f_test.h"
#include "calib/reprojection_cost.h"
#include "calib/view_correlation.h"
#include "test_util.h"

namespace insitu {
namespace {

// Upper percentage points of the F distribution (e.g. NIST/SEMATECH e-Handbook, Table 1.3.6.7.2).
TEST(FTest, MatchesPublishedCriticalValues) {
  EXPECT_NEAR(f_distribution_sf(30.817, 2, 3), 0.01, 1e-4);
  EXPECT_NEAR(f_distribution_sf(4.965, 1, 10), 0.05, 1e-4);
  EXPECT_NEAR(f_distribution_sf(7.559, 2, 10), 0.01, 1e-4);
  EXPECT_NEAR(f_distribution_sf(3.098, 3, 20), 0.05, 1e-4);
  EXPECT_NEAR(f_distribution_sf(161.448, 1, 1), 0.05, 1e-4);
  EXPECT_DOUBLE_EQ(f_distribution_sf(0, 2, 5), 1.0);
  EXPECT_DOUBLE_EQ(f_distribution_sf(INFINITY, 2, 5), 0.0);
  // I_x(1, 1) = x; I_½(a, a) = ½.
  EXPECT_NEAR(regularized_incomplete_beta(1, 1, 0.3), 0.3, 1e-14);
  EXPECT_NEAR(regularized_incomplete_beta(7.5, 7.5, 0.5), 0.5, 1e-12);
}

}  // namespace
}  // namespace insitu
