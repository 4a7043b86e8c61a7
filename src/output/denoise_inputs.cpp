#include "output/denoise_inputs.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/colour.h"
#include "output/composite.h"

namespace insitu::denoise_detail {
namespace {

// The depth of a sample that met nothing (kNoHitDepth) would swamp a window's scale.
constexpr float kMaxFeatureDepth = 1e3f;
// The albedo below which the guide is not divided further (a black object, a pixel that met
// nothing).
constexpr double kMinGuideAlbedo = 0.02;

// The variance, box-filtered over 5 × 5 pixels: a pixel's own estimate from a few samples is
// itself noisy, and the distance divides by it (Rousselle et al. 2012 filter theirs likewise).
// A pixel keeps its own estimate where that is larger: a firefly's variance spread over 25
// pixels would make it look unlike its neighbours, so it kept its own value (a speckle of 45 %
// far from the objects at 16 spp; 11 % with the maximum).
std::vector<float> prefiltered_variance(const Image& variance) {
  cv::Mat in(variance.height, variance.width, CV_32F, const_cast<float*>(variance.data.data()));
  cv::Mat box;
  cv::blur(in, box, cv::Size(5, 5), cv::Point(-1, -1), cv::BORDER_REPLICATE);
  cv::Mat out = cv::max(box, in);
  return std::vector<float>(out.begin<float>(), out.end<float>());
}

}  // namespace

Inputs gather(const Image& photo, const Image& comp, const Image& variance, const RenderLayers& l, int s) {
  Inputs in;
  in.width = comp.width, in.height = comp.height, in.change = Image(comp.width, comp.height, 3);
  in.variance = prefiltered_variance(variance);
  const Image touched = touched_mask(l);
  const std::size_t n = std::size_t(comp.width) * comp.height;
  in.luminance.resize(n), in.estimated.resize(n), in.features.resize(n * kFeatures);
  for (int y = 0; y < comp.height; ++y)
    for (int x = 0; x < comp.width; ++x) {
      const std::size_t i = in.index(x, y);
      const Rgb albedo = l.albedo.rgb(x, y), normal = l.normal.rgb(x, y);
      const float alpha = *l.alpha.at(x, y);
      in.change.set_rgb(x, y, comp.rgb(x, y) - (1 - alpha) * photo.rgb(x, y));
      const double a = std::max(double(luminance(albedo)), kMinGuideAlbedo);
      in.luminance[i] = float(luminance(in.change.rgb(x, y)) / a);
      // A pixel the render left untouched beside ones it touched: all its samples agreed, so its
      // own variance is 0, but a change they all missed is not excluded (a shadow that blocks a
      // tenth of a broad light is missed by 16 samples with probability 0.9¹⁶ = 19 %). It takes
      // its neighbours' variance (the prefilter's 5 × 5 box) and is estimated like them. With
      // nothing touched within 2 pixels, a pixel is the photo's, exact.
      in.estimated[i] = *touched.at(x, y) != 0 || in.variance[i] > 0;
      in.variance[i] = in.estimated[i] ? float(in.variance[i] / (a * a)) : 0.0f;
      float* f = &in.features[i * kFeatures];
      for (int c = 0; c < 3; ++c) f[c] = albedo[c], f[3 + c] = normal[c];
      f[6] = std::min(*l.depth.at(x, y), kMaxFeatureDepth);
      f[7] = alpha;
      f[8] = (1 - alpha) * luminance(photo.rgb(x, y));
      f[9] = (float(x) + 0.5f) / float(s), f[10] = (float(y) + 0.5f) / float(s);
    }
  return in;
}

Inputs blocks_of(const Inputs& px, int s) {
  Inputs b;
  b.width = (px.width + s - 1) / s, b.height = (px.height + s - 1) / s;
  b.change = Image(b.width, b.height, 3, 0.0f);
  const std::size_t n = std::size_t(b.width) * b.height;
  b.luminance.assign(n, 0.0f), b.variance.assign(n, 0.0f), b.features.assign(n * kFeatures, 0.0f);
  b.estimated.assign(n, 0);
  for (int by = 0; by < b.height; ++by)
    for (int bx = 0; bx < b.width; ++bx) {
      const int x0 = bx * s, y0 = by * s, x1 = std::min(px.width, x0 + s), y1 = std::min(px.height, y0 + s);
      const std::size_t k = b.index(bx, by);
      double change[3] = {0, 0, 0}, guide = 0, variance = 0, features[kFeatures] = {};
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          const std::size_t i = px.index(x, y);
          const Rgb c = px.change.rgb(x, y);
          for (int ch = 0; ch < 3; ++ch) change[ch] += c[ch];
          guide += px.luminance[i], variance += px.variance[i];
          for (int d = 0; d < kFeatures; ++d) features[d] += px.features[i * kFeatures + std::size_t(d)];
          b.estimated[k] |= px.estimated[i];
        }
      const double count = double((x1 - x0) * (y1 - y0));
      b.change.set_rgb(bx, by, Rgb(float(change[0] / count), float(change[1] / count), float(change[2] / count)));
      b.luminance[k] = float(guide / count), b.variance[k] = float(variance / (count * count));
      for (int d = 0; d < kFeatures; ++d) b.features[k * kFeatures + std::size_t(d)] = float(features[d] / count);
    }
  return b;
}

int auto_block_size(int width, int height) {
  return std::clamp(int(std::lround(std::min(width, height) / 480.0)), 1, 4);
}

}  // namespace insitu::denoise_detail
