// HDR from exposure brackets, and the camera response that also linearizes the photo.
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

// A pixel is clipped where a channel is at the top of the stored range (>= 254.5/255 for 8-bit,
// 65534.5/65535 for 16-bit): radiance there is only a lower bound. Float files clip nowhere.
//
// 1 channel: how near each pixel is to clipping. 0 where its largest channel is below 0.9 of the
// range, rising linearly to 1 at the top code (clipped). The start is a choice: there the merge's
// hat weight min(z, 1 − z) (Debevec and Malik 1997) is at most 0.1 and the response curves are
// least constrained; the weight reaches zero only at the last code.
Image clipped_degree(const ImageFile& file);
// 1 (in every one of its `channels`) where a pixel is clipped, else 0 (clipped_degree = 1).
Image clipped_mask(const ImageFile& file, int channels = 3);
// The fraction of pixels clipped: of the file, or of its clipped_mask.
double clipped_fraction(const ImageFile& file);
double clipped_fraction(const Image& mask);

}  // namespace insitu
