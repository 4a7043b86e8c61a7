// The legacy per-face Gaussian blur (light/gaussian_irradiance.h).
#include <gtest/gtest.h>

#include <random>

#include "light/gaussian_irradiance.h"
#include "integrators/registry.h"
#include "render/mesh.h"
#include "test_util.h"

namespace insitu {
namespace {

// The slow, obviously correct legacy blur of one face: a direct 2-D sum with OpenCV's Gaussian
// for sigma = 0, sigma = 0.3((k−1)/2 − 1) + 0.8, weights normalized, borders reflected without
// repeating the edge texel (BORDER_REFLECT_101: ... 2 1 | 0 1 2 ... n−1 | n−2 ...).
Image reference_blur(const Image& face, int k) {
  const double sigma = 0.3 * ((k - 1) * 0.5 - 1) + 0.8;
  const int n = face.width, r = k / 2;
  std::vector<double> w(static_cast<std::size_t>(k));
  double sum = 0;
  for (int i = 0; i < k; ++i) sum += w[std::size_t(i)] = std::exp(-double((i - r) * (i - r)) / (2 * sigma * sigma));
  for (double& x : w) x /= sum;
  auto reflect = [n](int i) {
    while (i < 0 || i >= n) i = i < 0 ? -i : 2 * (n - 1) - i;
    return i;
  };
  Image out(n, n, 3);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      for (int c = 0; c < 3; ++c) {
        double acc = 0;
        for (int dy = -r; dy <= r; ++dy)
          for (int dx = -r; dx <= r; ++dx)
            acc += w[std::size_t(dy + r)] * w[std::size_t(dx + r)] * face.at(reflect(x + dx), reflect(y + dy))[c];
        out.at(x, y)[c] = float(acc);
      }
  return out;
}

TEST(LegacyGaussian, KernelAsWideAsTheFace) {
  EXPECT_EQ(legacy_kernel_size(1), 1);
  EXPECT_EQ(legacy_kernel_size(8), 7);
  EXPECT_EQ(legacy_kernel_size(9), 9);
  EXPECT_EQ(legacy_kernel_size(256), 255);
}

TEST(LegacyGaussian, MatchesTheDirectSumOnEveryFace) {
  for (int n : {5, 8, 13}) {
    CubeMap cube(n);
    std::mt19937 rng{static_cast<unsigned>(n)};
    std::uniform_real_distribution<float> u(0, 10);
    for (int f = 0; f < 6; ++f)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) cube.set_texel(f, i, j, Rgb(u(rng), u(rng), u(rng)));
    cube.update_borders();
    const CubeMap blurred = gaussian_blur_faces(cube);
    for (int f = 0; f < 6; ++f) {
      const Image ref = reference_blur(cube.face_image(f), legacy_kernel_size(n));
      const Image got = blurred.face_image(f);
      for (std::size_t i = 0; i < ref.data.size(); ++i)
        ASSERT_NEAR(got.data[i], ref.data[i], 1e-4f) << "n " << n << " face " << f;
    }
  }
}

}  // namespace
}  // namespace insitu
