// HDR from exposure brackets, and the camera response that also linearizes the photo (issue 4).
//
// Debevec & Malik 1997 through OpenCV: CalibrateDebevec recovers the response g (pixel value ->
// relative exposure) from one set of aligned brackets; MergeDebevec combines a set into relative
// radiance, Σ_b w(Z_b) g(Z_b)/k_b / Σ_b w(Z_b), with k_b each bracket's relative exposure
// (t·ISO/N², or the given time). OpenCV's g is 1 at pixel value 128 in every channel; we scale it so
// that g(128) = srgb_to_linear(128/255), which keeps bracketed and single images in one unit.
#pragma once
#include <array>
#include <vector>

#include "core/image.h"

namespace insitu {

struct ResponseCurve {
  std::array<std::array<float, 256>, 3> g;  // per channel, value -> linear
  Rgb at(int value) const { return {g[0][std::size_t(value)], g[1][std::size_t(value)], g[2][std::size_t(value)]}; }
};

// The sRGB decoding as a response curve (what single 8-bit images use without brackets).
ResponseCurve srgb_response();

// All brackets 8-bit, of one size (InputError naming the first that differs).
ResponseCurve recover_response(const std::vector<ImageFile>& brackets, const std::vector<double>& exposures);
Image merge_brackets(const std::vector<ImageFile>& brackets, const std::vector<double>& exposures,
                     const ResponseCurve& response);
// Where the shortest bracket is clipped (255) the merged value is the lower bound g(255)/k_min.
//
// An 8-bit image through a response curve.
Image linearize_with_response(const ImageFile& file, const ResponseCurve& response);

// The fraction of pixels with a channel at the top of the stored range (>= 254.5/255 for 8-bit):
// radiance there is only a lower bound.
double clipped_fraction(const ImageFile& file);
// 1 (in every channel) where a pixel is clipped so, else 0; all 0 for float files.
Image clipped_mask(const ImageFile& file);

}  // namespace insitu
