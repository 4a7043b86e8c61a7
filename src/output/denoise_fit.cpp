#include "output/denoise_fit.h"

#include <Eigen/Dense>
#include <cmath>

namespace insitu::denoise_detail {
namespace {

template <int N>
using Row = Eigen::Matrix<double, N, 1>;
template <int N>
using Normal = Eigen::Matrix<double, N, N>;

// x = (1, scaled (f − f_i)): the regressor of a pixel (or block) with features f in the window of
// the one with features f_i.
template <int N>
Row<N> regressor(const std::array<double, kFeatures>& scale, const float* f, const float* fi) {
  Row<N> r;
  r[0] = 1;
  for (int d = 0; d + 1 < N; ++d) r[d + 1] = scale[std::size_t(d)] * (double(f[d]) - fi[d]);
  return r;
}

// The ridge on every coefficient but the constant, and on the features left out (scale 0), whose
// rows are then only the ridge.
template <int N>
Normal<N> ridge_matrix(const Window& w, const DenoiseSettings& s) {
  Normal<N> r = Normal<N>::Zero();
  for (int d = 0; d + 1 < N; ++d) r(d + 1, d + 1) = s.ridge * w.total + (w.scale[std::size_t(d)] == 0 ? 1.0 : 0.0);
  return r;
}

// The normal equations' sums over the window: A = Σ_j w_j x_j x_jᵀ (its lower triangle, what LDLT
// reads) and Σ_j w_j x_j T_jᵀ. A tap's products are summed in a packed array whose fixed loops the
// compiler unrolls: Eigen's general rank update took three times as long.
template <int N>
struct Sums {
  Normal<N> a;
  Eigen::Matrix<double, N, 3> rhs;
};
template <int N>
Sums<N> weighted_sums(const Inputs& in, const Window& w, int x, int y) {
  std::array<double, N*(N + 1) / 2> sum{};
  Sums<N> out{Normal<N>::Zero(), Eigen::Matrix<double, N, 3>::Zero()};
  const float* fi = in.f(x, y);
  std::size_t k = 0;
  for (int yy = w.y0; yy <= w.y1; ++yy)
    for (int xx = w.x0; xx <= w.x1; ++xx) {
      const double wt = w.weight[k++];
      const Row<N> r = regressor<N>(w.scale, in.f(xx, yy), fi);
      std::size_t p = 0;
      for (int i = 0; i < N; ++i) {
        const double wr = wt * r[i];
        for (int j = 0; j <= i; ++j) sum[p++] += wr * r[j];
      }
      const Rgb t = in.change.rgb(xx, yy);
      for (int c = 0; c < 3; ++c) out.rhs.col(c) += (wt * double(t[c])) * r;
    }
  std::size_t p = 0;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j <= i; ++j) out.a(i, j) = sum[p++];
  return out;
}

// Kish's effective sample size of the window's weights, (Σ w)² / Σ w².
double effective_taps(const Window& w) {
  double sum2 = 0;
  for (double x : w.weight) sum2 += x * x;
  return sum2 > 0 ? w.total * w.total / sum2 : 0.0;
}

}  // namespace

template <int N>
Fit<N> fit_window(const Inputs& in, const DenoiseSettings& s, const Window& w, int x, int y) {
  Sums<N> sums = weighted_sums<N>(in, w, x, y);
  sums.a += ridge_matrix<N>(w, s);
  const auto ldlt = sums.a.template selfadjointView<Eigen::Lower>().ldlt();
  Fit<N> fit{ldlt.solve(sums.rhs), w.scale, effective_taps(w), 0.0};
  const Row<N> u = ldlt.solve(Row<N>::Unit(0));
  const float* fi = in.f(x, y);
  std::size_t k = 0;
  for (int yy = w.y0; yy <= w.y1; ++yy)
    for (int xx = w.x0; xx <= w.x1; ++xx) {
      const double l = w.weight[k++] * u.dot(regressor<N>(w.scale, in.f(xx, yy), fi));
      fit.variance += l * l * in.variance[in.index(xx, yy)];
    }
  return fit;
}

template <int N>
Fit<N> reference_fit(const Inputs& in, const DenoiseSettings& s, int x, int y) {
  const Window w = window_of(in, s, x, y);
  const int n = int(w.weight.size());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n + N, N);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + N, 3);
  int k = 0;
  for (int yy = w.y0; yy <= w.y1; ++yy)
    for (int xx = w.x0; xx <= w.x1; ++xx, ++k) {
      const double sw = std::sqrt(w.weight[std::size_t(k)]);
      m.row(k) = sw * regressor<N>(w.scale, in.f(xx, yy), in.f(x, y)).transpose();
      for (int c = 0; c < 3; ++c) rhs(k, c) = sw * in.change.rgb(xx, yy)[c];
    }
  m.bottomRows(N) = ridge_matrix<N>(w, s).cwiseSqrt();
  return {m.colPivHouseholderQr().solve(rhs), w.scale, effective_taps(w), 0.0};
}

template <int N>
Rgb predict(const Fit<N>& fit, const float* f, const float* f_c) {
  const Eigen::Matrix<double, 1, 3> t = regressor<N>(fit.scale, f, f_c).transpose() * fit.beta;
  return {float(t[0]), float(t[1]), float(t[2])};
}

template Fit<kPlainFit> fit_window(const Inputs&, const DenoiseSettings&, const Window&, int, int);
template Fit<kPositionFit> fit_window(const Inputs&, const DenoiseSettings&, const Window&, int, int);
template Fit<kPlainFit> reference_fit(const Inputs&, const DenoiseSettings&, int, int);
template Fit<kPositionFit> reference_fit(const Inputs&, const DenoiseSettings&, int, int);
template Rgb predict(const Fit<kPlainFit>&, const float*, const float*);
template Rgb predict(const Fit<kPositionFit>&, const float*, const float*);

}  // namespace insitu::denoise_detail
