#include "output/denoise.h"

#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

#include "core/colour.h"
#include "output/composite.h"

namespace insitu {
namespace {

// albedo RGB, normal XYZ, depth, coverage, photo luminance behind the objects; and the constant.
constexpr int kFeatures = 9, kUnknowns = kFeatures + 1;
using Row = Eigen::Matrix<double, kUnknowns, 1>;
using Normal = Eigen::Matrix<double, kUnknowns, kUnknowns>;
// The depth of a sample that met nothing (kNoHitDepth) would swamp a window's scale.
constexpr float kMaxFeatureDepth = 1e3f;
// ε of the patch distance, relative to the pixels' squared luminance: neighbours whose values
// are exact (v = 0) count as alike within about 1 %.
constexpr double kRelativeEpsilon = 1e-4;
// The albedo below which the guide is not divided further (a black object, a pixel that met
// nothing).
constexpr double kMinGuideAlbedo = 0.02;

struct Inputs {
  int width = 0, height = 0;
  const Image* photo = nullptr;
  Image change;  // RGB: the composite less the photo behind the objects, C − (1 − α) P
  // Per pixel: the guide (the luminance divided by the albedo's) and its variance; the features.
  std::vector<float> luminance, variance, features;
  std::vector<std::uint8_t> touched;
  const float* f(int x, int y) const { return &features[(std::size_t(y) * width + x) * kFeatures]; }
  std::size_t index(int x, int y) const { return std::size_t(y) * width + x; }
};

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

Inputs gather(const Image& photo, const Image& comp, const Image& variance, const RenderLayers& l) {
  Inputs in;
  in.width = comp.width, in.height = comp.height, in.change = Image(comp.width, comp.height, 3);
  in.photo = &photo;
  in.variance = prefiltered_variance(variance);
  const Image touched = touched_mask(l);
  const std::size_t n = std::size_t(comp.width) * comp.height;
  in.luminance.resize(n), in.touched.resize(n), in.features.resize(n * kFeatures);
  for (int y = 0; y < comp.height; ++y)
    for (int x = 0; x < comp.width; ++x) {
      const std::size_t i = in.index(x, y);
      const Rgb albedo = l.albedo.rgb(x, y), normal = l.normal.rgb(x, y);
      const float alpha = *l.alpha.at(x, y);
      in.change.set_rgb(x, y, comp.rgb(x, y) - (1 - alpha) * photo.rgb(x, y));
      const double a = std::max(double(luminance(albedo)), kMinGuideAlbedo);
      in.luminance[i] = float(luminance(in.change.rgb(x, y)) / a);
      in.touched[i] = *touched.at(x, y) != 0;
      in.variance[i] = in.touched[i] ? float(in.variance[i] / (a * a)) : 0.0f;  // untouched: the photo's, exact
      float* f = &in.features[i * kFeatures];
      for (int c = 0; c < 3; ++c) f[c] = albedo[c], f[3 + c] = normal[c];
      f[6] = std::min(*l.depth.at(x, y), kMaxFeatureDepth);
      f[7] = alpha;
      f[8] = (1 - alpha) * luminance(photo.rgb(x, y));
    }
  return in;
}

// Rousselle et al. 2012's patch distance d²_ij over 3 × 3 patches (clamped at the borders).
double patch_distance(const Inputs& in, int xi, int yi, int xj, int yj, double k2) {
  double sum = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const std::size_t a = in.index(std::clamp(xi + dx, 0, in.width - 1), std::clamp(yi + dy, 0, in.height - 1));
      const std::size_t b = in.index(std::clamp(xj + dx, 0, in.width - 1), std::clamp(yj + dy, 0, in.height - 1));
      const double ya = in.luminance[a], yb = in.luminance[b], va = in.variance[a], vb = in.variance[b];
      const double eps = kRelativeEpsilon * 0.5 * (ya * ya + yb * yb) + 1e-30;
      sum += ((ya - yb) * (ya - yb) - (va + std::min(va, vb))) / (eps + k2 * (va + vb));
    }
  return sum / 9;
}

// The window of pixel (x, y): its pixels, their NL-means weights, and the scale of each feature.
struct Window {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // inclusive
  std::vector<double> weight;          // row by row over the window
  std::array<double, kFeatures> scale{};
  double total = 0;
};

Window window_of(const Inputs& in, const DenoiseSettings& s, int x, int y) {
  Window w;
  w.x0 = std::max(0, x - s.radius), w.x1 = std::min(in.width - 1, x + s.radius);
  w.y0 = std::max(0, y - s.radius), w.y1 = std::min(in.height - 1, y + s.radius);
  const float* fi = in.f(x, y);
  std::array<double, kFeatures> range{};
  for (int yy = w.y0; yy <= w.y1; ++yy)
    for (int xx = w.x0; xx <= w.x1; ++xx) {
      const double wt = std::exp(-std::max(0.0, patch_distance(in, x, y, xx, yy, s.k * s.k)));
      w.weight.push_back(wt), w.total += wt;
      const float* fj = in.f(xx, yy);
      for (int d = 0; d < kFeatures; ++d) range[d] = std::max(range[d], double(std::abs(fj[d] - fi[d])));
    }
  // A feature that does not vary over the window (relative to its size) is left out of the fit.
  for (int d = 0; d < kFeatures; ++d) w.scale[d] = range[d] > 1e-6 * (std::abs(fi[d]) + 1e-3) ? 1.0 / range[d] : 0.0;
  return w;
}

// x_j = (1, scaled (f_j − f_i)).
Row regressor(const Inputs& in, const Window& w, int x, int y, int xx, int yy) {
  Row r;
  r[0] = 1;
  const float* fi = in.f(x, y);
  const float* fj = in.f(xx, yy);
  for (int d = 0; d < kFeatures; ++d) r[d + 1] = w.scale[d] * (double(fj[d]) - fi[d]);
  return r;
}

// The ridge on every coefficient but the constant, and on the features left out (scale 0), whose
// rows are then only the ridge.
Normal ridge_matrix(const Window& w, const DenoiseSettings& s) {
  Normal r = Normal::Zero();
  for (int d = 0; d < kFeatures; ++d) r(d + 1, d + 1) = s.ridge * w.total + (w.scale[d] == 0 ? 1.0 : 0.0);
  return r;
}

struct PixelOut {
  Rgb value = Rgb::Zero();
  double variance = 0;
};

PixelOut denoise_one(const Inputs& in, const DenoiseSettings& s, int x, int y) {
  const Window w = window_of(in, s, x, y);
  Normal a = ridge_matrix(w, s);
  std::size_t k = 0;
  for (int yy = w.y0; yy <= w.y1; ++yy)
    for (int xx = w.x0; xx <= w.x1; ++xx) {
      const Row r = regressor(in, w, x, y, xx, yy);
      a.selfadjointView<Eigen::Lower>().rankUpdate(r, w.weight[k++]);
    }
  // u = A⁻¹ e₀; then β₀ = Σ_j w_j (uᵀ x_j) C_j.
  const Row u = a.selfadjointView<Eigen::Lower>().ldlt().solve(Row::Unit(0));
  PixelOut out;
  k = 0;
  for (int yy = w.y0; yy <= w.y1; ++yy)
    for (int xx = w.x0; xx <= w.x1; ++xx) {
      const double l = w.weight[k++] * u.dot(regressor(in, w, x, y, xx, yy));
      out.value += float(l) * in.change.rgb(xx, yy);
      out.variance += l * l * in.variance[in.index(xx, yy)];
    }
  out.value = (out.value + (1 - in.f(x, y)[7]) * in.photo->rgb(x, y)).max(0.0f);
  return out;
}

void check_sizes(const Image& photo, const Image& comp, const Image& variance, const RenderLayers& l) {
  const bool same = photo.width == comp.width && photo.height == comp.height && variance.width == comp.width &&
                    variance.height == comp.height && l.alpha.width == comp.width && l.alpha.height == comp.height;
  if (!same) throw std::logic_error("denoise: the photo, the composite and the layers differ in size");
}

}  // namespace

Denoised denoise_composite(const Image& photo, const Image& comp, const Image& variance, const RenderLayers& l,
                           const DenoiseSettings& s) {
  check_sizes(photo, comp, variance, l);
  const Inputs in = gather(photo, comp, variance, l);
  Denoised out{comp, Image(comp.width, comp.height, 1, 0.0f)};
  tbb::parallel_for(0, comp.height, [&](int y) {
    for (int x = 0; x < comp.width; ++x) {
      if (!in.touched[in.index(x, y)]) continue;
      const PixelOut p = denoise_one(in, s, x, y);
      out.composite.set_rgb(x, y, p.value);
      *out.variance.at(x, y) = float(p.variance);
    }
  });
  return out;
}

// The same weights and features, and β₀ from a QR solve of the weighted, ridge-augmented system
// [√W X; √R] β = [√W T; 0] for the change T = C − (1 − α) P, one channel at a time; then
// (1 − α) P + β₀.
Rgb denoise_pixel_reference(const Image& photo, const Image& comp, const Image& variance, const RenderLayers& l,
                            const DenoiseSettings& s, int x, int y) {
  check_sizes(photo, comp, variance, l);
  const Inputs in = gather(photo, comp, variance, l);
  if (!in.touched[in.index(x, y)]) return comp.rgb(x, y);
  const Window w = window_of(in, s, x, y);
  const int n = int(w.weight.size());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n + kUnknowns, kUnknowns);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + kUnknowns, 3);
  int k = 0;
  for (int yy = w.y0; yy <= w.y1; ++yy)
    for (int xx = w.x0; xx <= w.x1; ++xx, ++k) {
      const double sw = std::sqrt(w.weight[k]);
      m.row(k) = sw * regressor(in, w, x, y, xx, yy).transpose();
      for (int c = 0; c < 3; ++c) rhs(k, c) = sw * in.change.rgb(xx, yy)[c];
    }
  m.bottomRows(kUnknowns) = ridge_matrix(w, s).cwiseSqrt();
  const Eigen::MatrixXd beta = m.colPivHouseholderQr().solve(rhs);
  const Rgb behind = (1 - *l.alpha.at(x, y)) * photo.rgb(x, y);
  return (Rgb(float(beta(0, 0)), float(beta(0, 1)), float(beta(0, 2))) + behind).max(0.0f);
}

}  // namespace insitu
