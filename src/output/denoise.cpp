#include "output/denoise.h"

#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <stdexcept>

#include "output/denoise_inputs.h"
#include "output/denoise_weights.h"

namespace insitu {
namespace {

using namespace denoise_detail;

// The features and the constant.
constexpr int kUnknowns = kFeatures + 1;
using Row = Eigen::Matrix<double, kUnknowns, 1>;
using Normal = Eigen::Matrix<double, kUnknowns, kUnknowns>;
using Slopes = Eigen::Matrix<double, kUnknowns, 3>;  // β by RGB channel

// x = (1, scaled (f − f_i)): the regressor of a pixel (or block) with features f in the window of
// the one with features f_i.
Row regressor(const std::array<double, kFeatures>& scale, const float* f, const float* fi) {
  Row r;
  r[0] = 1;
  for (int d = 0; d < kFeatures; ++d) r[d + 1] = scale[std::size_t(d)] * (double(f[d]) - fi[d]);
  return r;
}

// The ridge on every coefficient but the constant, and on the features left out (scale 0), whose
// rows are then only the ridge.
Normal ridge_matrix(const Window& w, const DenoiseSettings& s) {
  Normal r = Normal::Zero();
  for (int d = 0; d < kFeatures; ++d) r(d + 1, d + 1) = s.ridge * w.total + (w.scale[d] == 0 ? 1.0 : 0.0);
  return r;
}

// The normal equations' sums over the window: A = Σ_j w_j x_j x_jᵀ (its lower triangle, what
// LDLT reads) and Σ_j w_j x_j T_jᵀ. A tap's 55 products are summed in a packed array whose fixed
// loops the compiler unrolls: Eigen's general rank update took three times as long.
struct Sums {
  Normal a;
  Slopes rhs;
};
Sums weighted_sums(const Inputs& in, const Window& w, int x, int y) {
  constexpr int kPacked = kUnknowns * (kUnknowns + 1) / 2;
  std::array<double, kPacked> sum{};
  Slopes rhs = Slopes::Zero();
  const float* fi = in.f(x, y);
  std::size_t k = 0;
  for (int yy = w.y0; yy <= w.y1; ++yy)
    for (int xx = w.x0; xx <= w.x1; ++xx) {
      const double wt = w.weight[k++];
      const Row r = regressor(w.scale, in.f(xx, yy), fi);
      std::size_t p = 0;
      for (int i = 0; i < kUnknowns; ++i) {
        const double wr = wt * r[i];
        for (int j = 0; j <= i; ++j) sum[p++] += wr * r[j];
      }
      const Rgb t = in.change.rgb(xx, yy);
      for (int c = 0; c < 3; ++c) rhs.col(c) += (wt * double(t[c])) * r;
    }
  Sums out{Normal::Zero(), rhs};
  std::size_t p = 0;
  for (int i = 0; i < kUnknowns; ++i)
    for (int j = 0; j <= i; ++j) out.a(i, j) = sum[p++];
  return out;
}

// One window's first-order fit, T_j ≈ x_jᵀ β, and the variance of its constant β₀ = Σ_j l_j T_j
// (l_j = w_j uᵀ x_j, u = A⁻¹ e₀), Σ_j l_j² v_j.
struct Fit {
  Slopes beta;
  std::array<double, kFeatures> scale{};
  double variance = 0;
};
Fit fit_window(const Inputs& in, const DenoiseSettings& s, const Window& w, int x, int y) {
  Sums sums = weighted_sums(in, w, x, y);
  sums.a += ridge_matrix(w, s);
  const auto ldlt = sums.a.selfadjointView<Eigen::Lower>().ldlt();
  Fit fit{ldlt.solve(sums.rhs), w.scale, 0.0};
  const Row u = ldlt.solve(Row::Unit(0));
  const float* fi = in.f(x, y);
  std::size_t k = 0;
  for (int yy = w.y0; yy <= w.y1; ++yy)
    for (int xx = w.x0; xx <= w.x1; ++xx) {
      const double l = w.weight[k++] * u.dot(regressor(w.scale, in.f(xx, yy), fi));
      fit.variance += l * l * in.variance[in.index(xx, yy)];
    }
  return fit;
}

// The fit's change at a pixel with features f, in the window centred on features f_c: the pixel's
// own features carry its texture, normal and edge within a block.
Rgb predict(const Fit& fit, const float* f, const float* f_c) {
  const Eigen::Matrix<double, 1, 3> t = regressor(fit.scale, f, f_c).transpose() * fit.beta;
  return {float(t[0]), float(t[1]), float(t[2])};
}

void check_sizes(const Image& photo, const Image& comp, const Image& variance, const RenderLayers& l) {
  const bool same = photo.width == comp.width && photo.height == comp.height && variance.width == comp.width &&
                    variance.height == comp.height && l.alpha.width == comp.width && l.alpha.height == comp.height;
  if (!same) throw std::logic_error("denoise: the photo, the composite and the layers differ in size");
}

int block_size(const DenoiseSettings& s, const Image& comp) {
  return s.block > 0 ? s.block : auto_block_size(comp.width, comp.height);
}

// The touched pixels of block (bx, by) from its fit: (1 − α) P + the predicted change.
void write_block(const Inputs& px, const Inputs& fitted, const Fit& fit, const Image& photo, int s, int bx, int by,
                 Denoised& out) {
  for (int y = by * s; y < std::min(px.height, (by + 1) * s); ++y)
    for (int x = bx * s; x < std::min(px.width, (bx + 1) * s); ++x) {
      if (!px.touched[px.index(x, y)]) continue;
      const Rgb t = predict(fit, px.f(x, y), fitted.f(bx, by));
      out.composite.set_rgb(x, y, ((1 - px.f(x, y)[7]) * photo.rgb(x, y) + t).max(0.0f));
      *out.variance.at(x, y) = float(fit.variance);
    }
}

}  // namespace

Denoised denoise_composite(const Image& photo, const Image& comp, const Image& variance, const RenderLayers& l,
                           const DenoiseSettings& s) {
  check_sizes(photo, comp, variance, l);
  const Inputs px = gather(photo, comp, variance, l);
  const int b = block_size(s, comp);
  const Inputs blocks = b > 1 ? blocks_of(px, b) : Inputs{};
  const Inputs& fitted = b > 1 ? blocks : px;
  Denoised out{comp, Image(comp.width, comp.height, 1, 0.0f)};
  // Strips of kStripRows rows (of blocks): the patch distances of a strip come from the box sums
  // of the rows around it, one above and one below (so 1.25 × the terms), and its weights take
  // 8 · 8 · width · (2R + 1)² bytes (7 MB for 640 wide, R = 6).
  constexpr int kStripRows = 8;
  tbb::parallel_for(0, (fitted.height + kStripRows - 1) / kStripRows, [&](int strip) {
    const int y0 = strip * kStripRows, y1 = std::min(fitted.height, y0 + kStripRows);
    const StripWeights weights = strip_weights(fitted, s, y0, y1);
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < fitted.width; ++x) {
        if (!fitted.touched[fitted.index(x, y)]) continue;
        const Fit fit = fit_window(fitted, s, window_from(fitted, s, weights, x, y), x, y);
        write_block(px, fitted, fit, photo, b, x, y, out);
      }
  });
  return out;
}

// The same weights and features, and β from a QR solve of the weighted, ridge-augmented system
// [√W X; √R] β = [√W T; 0] for the change T = C − (1 − α) P, one channel at a time, over the
// window of the pixel's block; then (1 − α) P + the fit at the pixel's own features.
Rgb denoise_pixel_reference(const Image& photo, const Image& comp, const Image& variance, const RenderLayers& l,
                            const DenoiseSettings& s, int x, int y) {
  check_sizes(photo, comp, variance, l);
  const Inputs px = gather(photo, comp, variance, l);
  if (!px.touched[px.index(x, y)]) return comp.rgb(x, y);
  const int b = block_size(s, comp);
  const Inputs fitted = b > 1 ? blocks_of(px, b) : px;
  const int bx = x / b, by = y / b;
  const Window w = window_of(fitted, s, bx, by);
  const int n = int(w.weight.size());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n + kUnknowns, kUnknowns);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + kUnknowns, 3);
  int k = 0;
  for (int yy = w.y0; yy <= w.y1; ++yy)
    for (int xx = w.x0; xx <= w.x1; ++xx, ++k) {
      const double sw = std::sqrt(w.weight[std::size_t(k)]);
      m.row(k) = sw * regressor(w.scale, fitted.f(xx, yy), fitted.f(bx, by)).transpose();
      for (int c = 0; c < 3; ++c) rhs(k, c) = sw * fitted.change.rgb(xx, yy)[c];
    }
  m.bottomRows(kUnknowns) = ridge_matrix(w, s).cwiseSqrt();
  const Fit fit{m.colPivHouseholderQr().solve(rhs), w.scale, 0.0};
  const Rgb behind = (1 - *l.alpha.at(x, y)) * photo.rgb(x, y);
  return (predict(fit, px.f(x, y), fitted.f(bx, by)) + behind).max(0.0f);
}

}  // namespace insitu
