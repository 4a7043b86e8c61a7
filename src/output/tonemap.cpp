#include "output/tonemap.h"

#include <algorithm>
#include <cmath>

#include "core/colour.h"

namespace insitu {

namespace {
constexpr double kDelta = 1e-6;

Rgb clean(const Rgb& c) {
  Rgb out;
  for (int k = 0; k < 3; ++k) out[k] = std::isfinite(c[k]) && c[k] > 0 ? c[k] : 0.0f;
  return out;
}
}  // namespace

double log_average_luminance(const Image& img) {
  double sum = 0;
  const std::size_t n = std::size_t(img.width) * img.height;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) sum += std::log(kDelta + double(luminance(clean(img.rgb(x, y)))));
  return n > 0 ? std::exp(sum / double(n)) : kDelta;
}

Image tonemap(const Image& img, const ToneMapSettings& s, const Image* clipped_photo) {
  const bool weighted = clipped_photo && clipped_photo->width == img.width && clipped_photo->height == img.height;
  Image out(img.width, img.height, 3);
  const double lavg = log_average_luminance(img);
  // Scaled luminance of every pixel, and its maximum.
  double key = s.key.value_or(default_key(s.op));
  double lmax = 0;
  if (s.op == ToneMap::kAdaptiveLog || s.op == ToneMap::kReinhard)
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) lmax = std::max(lmax, key * luminance(clean(img.rgb(x, y))) / lavg);
  const double exponent = std::log(s.bias) / std::log(0.5);
  const double drago_scale = lmax > 0 ? 1.0 / std::log10(lmax + 1) : 0.0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      Rgb c = clean(img.rgb(x, y));
      const double lw = luminance(c);
      if (weighted) {  // the clipped share neutral: C' = (1 − w)·C + w·Lw keeps the luminance Lw
        const float w = std::clamp(*clipped_photo->at(x, y), 0.0f, 1.0f);
        c = (1.0f - w) * c + Rgb::Constant(w * float(lw));
      }
      Rgb d = Rgb::Zero();
      if (s.op == ToneMap::kLinear) {
        d = c * float(key);
      } else if (lw > 0) {
        const double l = key * lw / lavg;
        double ld;
        if (s.op == ToneMap::kReinhard)
          ld = l / (1 + l);
        else
          ld = drago_scale * std::log(l + 1) / std::log(2 + 8 * std::pow(l / lmax, exponent));
        d = c * float(ld / lw);
      }
      for (int k = 0; k < 3; ++k) out.at(x, y)[k] = linear_to_srgb(d[k]);
    }
  return out;
}

}  // namespace insitu
