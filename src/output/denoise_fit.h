// The denoiser's first-order fit over one window (output/denoise.h): weighted least squares of the
// change, T_j ≈ x_jᵀ β with x_j = (1, scaled (f_j − f_i)), and a small ridge on the slopes. Over
// pixels the features are the shading ones; over blocks also the position, so that a block's fit
// carries the light's gradient to each of its pixels (a soft shadow, which no other feature
// sees, came out in steps of 3 pixels without it).
#pragma once
#include <Eigen/Core>
#include <array>

#include "core/colour.h"
#include "output/denoise.h"
#include "output/denoise_inputs.h"
#include "output/denoise_weights.h"

namespace insitu::denoise_detail {

// The unknowns: the constant and the shading features; with the position too.
constexpr int kPlainFit = kShadingFeatures + 1, kPositionFit = kFeatures + 1;

template <int N>
struct Fit {
  Eigen::Matrix<double, N, 3> beta;  // by RGB channel
  std::array<double, kFeatures> scale{};
  double effective_taps = 0;  // (Σ w)² / Σ w² over the window
  double variance = 0;        // of β₀ = Σ_j l_j T_j (l_j = w_j uᵀ x_j, u = A⁻¹ e₀): Σ_j l_j² v_j
};

// The fast form: the normal equations summed in packed form, solved by LDLT.
template <int N>
Fit<N> fit_window(const Inputs& in, const DenoiseSettings& s, const Window& w, int x, int y);

// The slow, obviously correct form: a column-pivoting QR of the weighted, ridge-augmented system
// [√W X; √R] β = [√W T; 0], over the window of (x, y) with each weight from its own patch
// distance. Its variance is not computed (0).
template <int N>
Fit<N> reference_fit(const Inputs& in, const DenoiseSettings& s, int x, int y);

// The fit's change at features f, in the window centred on features f_c: x(f)ᵀ β.
template <int N>
Rgb predict(const Fit<N>& fit, const float* f, const float* f_c);

}  // namespace insitu::denoise_detail
