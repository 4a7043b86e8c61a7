// Comparing two renders of one scene (`insitu compare`): error numbers and a picture of where.
//
//   RMSE            sqrt(mean over pixels and channels of (A − B)²), linear values
//   relative RMSE   RMSE / sqrt(mean of B²): B is the reference
//   SSIM            Wang et al. 2004 on the luminance of the sRGB-encoded images, Gaussian windows
//                   (σ = 1.5, 11×11), C1 = (0.01)², C2 = (0.03)²; the mean of the SSIM map
//   max error       the largest |A − B| of any channel
// over the whole image and over the pixels where the mask is non-zero.
#pragma once
#include <optional>

#include "core/image.h"

namespace insitu {

struct CompareNumbers {
  double rmse = 0, relative_rmse = 0, ssim = 1, max_error = 0;
  long pixels = 0;
};

struct CompareResult {
  CompareNumbers whole;
  std::optional<CompareNumbers> masked;
  Image error_luminance;  // 1 channel: |Y(A) − Y(B)|
};

// A, B linear RGB of one size; mask (any channels, non-zero = inside) of that size or empty.
CompareResult compare_images(const Image& a, const Image& b, const Image* mask = nullptr);

// A | B | heatmap of the luminance error (OpenCV's inferno map, 0 … max) with a colour bar and
// its scale, as an encoded image. A and B are shown as `a_display` and `b_display` (encoded values
// in [0, 1], e.g. the files as stored) when given, else encoded with the sRGB curve.
Image comparison_picture(const Image& a, const Image& b, const CompareResult& result, const Image* a_display = nullptr,
                         const Image* b_display = nullptr);

}  // namespace insitu
