// Compositing the rendered layers over the linearized photo P (Debevec 1998, differential
// rendering), and encoding the result.
//
// Per pixel, with O the objects premultiplied by their coverage α, and W, N the catcher's radiance
// with and without the objects (means over the pixel's samples, 0 where no catcher was seen):
//   additive:  C = O + (1 − α) P + (W − N)
//   ratio:     C = O + (1 − α) P · W/N      (per channel; where N = 0 the ratio is taken as 1:
//                                              nothing lit the catcher, so nothing can be removed)
// The ratio of means W̄/N̄ is a ratio estimator: where few samples saw the catcher (a pixel 99 %
// covered by a table leg) N̄ can sit near 0 and W̄/N̄ explode into a firefly. So the ratio form is
// used only where its estimated standard error, (1 − α) P · √Var(W̄/N̄) (delta method, with the
// correlation of W and N), is no larger than that of the additive form, √Var(W̄ − N̄), and at least
// two samples saw the catcher (one gives no variance at all); elsewhere the additive form, which
// estimates the same thing when the albedo comes from the photo. Where W = N bit for bit both
// variances are 0 and the ratio (exactly 1) is kept.
// Without a catcher (W = N = 0) both reduce to the alpha-over C = O + (1 − α) P. The ratio form
// does not depend on the catcher's albedo, so it is robust to errors in it; the additive form is
// what Debevec wrote. W and N come from the same random numbers, so they are bitwise equal where
// no object blocks or lights the catcher.
//
// Encoding for a display-referred output (PNG, JPEG): pixels the render left untouched (α = 0 and
// W = N bit for bit) keep the photo's own stored values, so they are bit-identical to the input;
// all others go through the inverse of the curve that linearized the photo — the response
// recovered from brackets when there is one, else the sRGB curve — so that a pixel changed only a
// little is encoded only a little differently.
#pragma once
#include <array>
#include "core/image.h"
#include "light/hdr_merge.h"
#include "output/settings.h"
#include "render/render.h"

namespace insitu {

Image composite(const Image& photo_linear, const RenderLayers& layers, CompositeMode mode);
// 1 channel: the variance of the composite's mean luminance at each pixel, as the layers estimate
// it: where the additive form is used, the variance layer's (that of O + W − N); where the ratio
// form is, ((1 − α) Y(P))² Var(W̄/N̄) (delta method), plus the variance layer where an object
// covers part of the pixel (an upper bound: it counts the catcher's W − N there too).
Image composite_variance(const Image& photo_linear, const RenderLayers& layers, CompositeMode mode);
// 1 channel: 1 where the render changed the pixel, 0 where it is the photo's.
Image touched_mask(const RenderLayers& layers);
// 1 channel: 1 on the objects (α > 0.01) and where the composite's luminance differs from the
// photo's by more than `threshold` of it (averaged over 3 × 3 pixels: the noise of a converged
// render stays below it), as tools/validate/metrics.py measures "objects + changed". With walls
// that catch, nearly every pixel is touched by a little; this is where the change shows.
Image changed_mask(const Image& photo_linear, const Image& composite_linear, const RenderLayers& layers,
                   double threshold = 0.03);
// W/N per channel (1 where N = 0): the shadow ratio layer.
Image shadow_ratio(const RenderLayers& layers);
// Whether the ratio form is the less noisy estimator at (x, y) (see above).
bool ratio_is_reliable(const Image& photo_linear, const RenderLayers& layers, int x, int y);

// 1 channel: how much of each pixel is the photo where it clipped: light/hdr_merge.h's
// clipped_degree of the photo times 1 − α of the objects. A clipped pixel's colour is unknown
// (the response curves map each channel's last code to a different radiance, so a white window
// is pink in linear light); tonemap() shows that share neutral.
Image clipped_photo_weight(const RenderLayers& layers, const ImageFile& photo);

Image encode_composite(const Image& composite_linear, const Image& touched, const ImageFile& photo,
                       const ResponseCurve* response = nullptr);
// The inverse of a response curve, continuous: the code value (0…1) whose g is `linear`, by
// interpolation between the two codes around it (g made non-decreasing first).
float inverse_response(const ResponseCurve& response, int channel, float linear);

// The same inverse, with g made non-decreasing once and the codes around a value found by
// bisection (8 steps, not a scan of up to 256): bit for bit inverse_response's value.
class InverseResponse {
 public:
  explicit InverseResponse(const ResponseCurve& response);
  float operator()(int channel, float linear) const;

 private:
  std::array<std::array<float, 256>, 3> rising_;  // running maximum of g, per channel
};

}  // namespace insitu
