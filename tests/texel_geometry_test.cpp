// Texel directions and solid angles of the cube (light/texel_geometry.h).
#include <gtest/gtest.h>

#include <random>

#include <opencv2/imgproc.hpp>

#include <cstring>

#include "light/environment.h"
#include "light/equirect.h"
#include "light/gaussian_irradiance.h"
#include "light/irradiance.h"
#include "core/sampler.h"
#include "test_util.h"
#include "light/texel_geometry.h"

namespace insitu {
namespace {

// The table (corners shared between texels) against the texel-by-texel formula.
TEST(TexelGeometry, FaceTableIsTheTexelFormula) {
  for (int n : {1, 2, 7, 64}) {
    const std::vector<double> omega = face_solid_angles(n);
    ASSERT_EQ(omega.size(), std::size_t(n) * std::size_t(n));
    double sum = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        EXPECT_NEAR(omega[std::size_t(j) * std::size_t(n) + std::size_t(i)], texel_solid_angle(i, j, n), 1e-15)
            << n << " " << i << " " << j;
        sum += omega[std::size_t(j) * std::size_t(n) + std::size_t(i)];
      }
    EXPECT_NEAR(sum, 4 * kPi / 6, 1e-12);  // a face is a sixth of the sphere
  }
}

TEST(TexelGeometry, SolidAnglesAndLambertVectorsSumAsTheSphere) {
  for (int n : {1, 3, 16}) {
    double omega = 0;
    Vec3d phi = Vec3d::Zero();
    for (int f = 0; f < 6; ++f)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          omega += texel_solid_angle(i, j, n);
          const Vec3d v = texel_vector_irradiance(f, i, j, n);
          phi += v;
          EXPECT_LE(v.norm(), texel_solid_angle(i, j, n) + 1e-15);
        }
    EXPECT_NEAR(omega, 4 * kPi, 1e-12);
    EXPECT_NEAR(phi.norm(), 0.0, 1e-12);
  }
  // A whole face seen from its centre's normal: Lambert's vector length is the one-face form
  // factor times π, and it equals the full-hemisphere-clipped integral for the face's own axis.
  EXPECT_NEAR(texel_vector_irradiance(kPosY, 0, 0, 1).y(), 2 * std::sqrt(2.0) * std::atan(1 / std::sqrt(2.0)), 1e-12);
}

}  // namespace
}  // namespace insitu
