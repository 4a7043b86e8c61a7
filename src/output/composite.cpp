#include "output/composite.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "core/colour.h"
#include "light/hdr_merge.h"

namespace insitu {

Image shadow_ratio(const RenderLayers& l) {
  Image r(l.with_objects.width, l.with_objects.height, 3, 1.0f);
  for (std::size_t i = 0; i < r.data.size(); ++i)
    if (l.without_objects.data[i] > 0) r.data[i] = l.with_objects.data[i] / l.without_objects.data[i];
  return r;
}

bool ratio_is_reliable(const Image& photo, const RenderLayers& l, int x, int y) {
  if (l.catcher_samples.data.empty()) return true;  // layers without the statistics: as before
  if (*l.catcher_samples.at(x, y) < 2) return *l.catcher_samples.at(x, y) == 0;
  const double scale = (1.0 - *l.alpha.at(x, y)) * luminance(photo.rgb(x, y));
  return scale * scale * *l.ratio_variance.at(x, y) <= *l.difference_variance.at(x, y);
}

Image composite(const Image& photo, const RenderLayers& l, CompositeMode mode) {
  if (photo.width != l.objects.width || photo.height != l.objects.height)
    throw std::logic_error("composite: the photo and the layers differ in size");
  const Image ratio = shadow_ratio(l);
  Image out(photo.width, photo.height, 3);
  for (int y = 0; y < photo.height; ++y)
    for (int x = 0; x < photo.width; ++x) {
      const float a = *l.alpha.at(x, y);
      const bool additive = mode == CompositeMode::kAdditive || !ratio_is_reliable(photo, l, x, y);
      const Rgb background =
          additive ? Rgb((1.0f - a) * photo.rgb(x, y) + l.with_objects.rgb(x, y) - l.without_objects.rgb(x, y))
                   : Rgb((1.0f - a) * photo.rgb(x, y) * ratio.rgb(x, y));
      out.set_rgb(x, y, (l.objects.rgb(x, y) + background).max(0.0f));
    }
  return out;
}

Image composite_variance(const Image& photo, const RenderLayers& l, CompositeMode mode) {
  Image v(photo.width, photo.height, 1, 0.0f);
  for (int y = 0; y < photo.height; ++y)
    for (int x = 0; x < photo.width; ++x) {
      const double a = *l.alpha.at(x, y), layer = *l.variance.at(x, y);
      if (mode == CompositeMode::kAdditive || l.ratio_variance.data.empty() || !ratio_is_reliable(photo, l, x, y)) {
        *v.at(x, y) = float(layer);
        continue;
      }
      const double scale = (1 - a) * luminance(photo.rgb(x, y));
      *v.at(x, y) = float(scale * scale * *l.ratio_variance.at(x, y) + (a > 0 ? layer : 0.0));
    }
  return v;
}

Image touched_mask(const RenderLayers& l) {
  Image m(l.alpha.width, l.alpha.height, 1, 0.0f);
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      bool touched = *l.alpha.at(x, y) != 0.0f;
      for (int c = 0; c < 3; ++c) touched |= l.with_objects.at(x, y)[c] != l.without_objects.at(x, y)[c];
      *m.at(x, y) = touched ? 1.0f : 0.0f;
    }
  return m;
}

Image changed_mask(const Image& photo, const Image& comp, const RenderLayers& l, double threshold) {
  const int w = photo.width, h = photo.height;
  Image m(w, h, 1, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double diff = 0, base = 0;
      int n = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
          diff += std::abs(luminance(comp.rgb(xx, yy)) - luminance(photo.rgb(xx, yy)));
          ++n;
        }
      base = std::max(double(luminance(photo.rgb(x, y))), 1e-6);
      *m.at(x, y) = *l.alpha.at(x, y) > 0.01f || diff / n > threshold * base ? 1.0f : 0.0f;
    }
  return m;
}

float inverse_response(const ResponseCurve& r, int channel, float v) {
  const auto& g = r.g[std::size_t(channel)];
  if (!(v > g[0])) return 0.0f;
  // Running maximum: the curve as a non-decreasing function.
  float prev = g[0];
  for (int z = 1; z < 256; ++z) {
    const float cur = std::max(prev, g[std::size_t(z)]);
    if (v <= cur) return (float(z - 1) + (cur > prev ? (v - prev) / (cur - prev) : 1.0f)) / 255.0f;
    prev = cur;
  }
  return 1.0f;
}

InverseResponse::InverseResponse(const ResponseCurve& r) {
  for (std::size_t k = 0; k < 3; ++k) {
    rising_[k][0] = r.g[k][0];
    for (std::size_t z = 1; z < 256; ++z) rising_[k][z] = std::max(rising_[k][z - 1], r.g[k][z]);
  }
}

// inverse_response's scan ends at the first z ≥ 1 with v ≤ the running maximum at z: a lower bound.
float InverseResponse::operator()(int channel, float v) const {
  const auto& m = rising_[std::size_t(channel)];
  if (!(v > m[0])) return 0.0f;
  const auto it = std::lower_bound(m.begin() + 1, m.end(), v);
  if (it == m.end()) return 1.0f;
  const int z = int(it - m.begin());
  const float cur = *it, prev = m[std::size_t(z - 1)];
  return (float(z - 1) + (cur > prev ? (v - prev) / (cur - prev) : 1.0f)) / 255.0f;
}

Image clipped_photo_weight(const RenderLayers& l, const ImageFile& photo) {
  Image w = clipped_degree(photo);
  for (int y = 0; y < w.height; ++y)
    for (int x = 0; x < w.width; ++x) *w.at(x, y) *= 1.0f - std::clamp(*l.alpha.at(x, y), 0.0f, 1.0f);
  return w;
}

Image encode_composite(const Image& c, const Image& touched, const ImageFile& photo, const ResponseCurve* response) {
  const bool use_response = response && photo.display_referred && photo.bits == 8;
  const std::optional<InverseResponse> inverse =
      use_response ? std::optional<InverseResponse>(*response) : std::nullopt;
  Image out(c.width, c.height, 3);
  tbb::parallel_for(0, c.height, [&](int y) {
    for (int x = 0; x < c.width; ++x) {
      const bool untouched = *touched.at(x, y) == 0.0f;
      for (int k = 0; k < 3; ++k) {
        if (untouched && photo.display_referred)
          out.at(x, y)[k] = photo.stored.at(x, y)[k];
        else
          out.at(x, y)[k] = inverse ? (*inverse)(k, c.at(x, y)[k]) : linear_to_srgb(c.at(x, y)[k]);
      }
    }
  });
  return out;
}

}  // namespace insitu
