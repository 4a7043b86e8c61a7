// A feature-guided denoiser for the composite: non-local-means weights on the noisy colour and a
// weighted first-order regression on noise-free features, evaluated at the pixel (the NL-means
// regression Cycles used before OpenImageDenoise, and the first-order fit of Bitterli et al. 2016,
// "Nonlinearly weighted first-order regression for denoising Monte Carlo renderings", NFOR).
// docs/denoise.md has the derivation, the choices and the measured bias.
//
// Per changed pixel i, over the window N(i) of (2R + 1)² pixels j:
//   weight   w_ij = exp(−max(0, d²_ij)), Rousselle et al. 2012's patch distance
//            ("Adaptive rendering with non-local means filtering") over 3 × 3 patches of the
//            guide: the change's luminance divided by the albedo's (the texture demodulated, as
//            Zimmer et al. 2015 and Bako et al. 2017 do: a textured floor's pixels then look
//            alike), with the variance of its mean (output/denoise_weights.h);
//   fit      T_j ≈ β₀ + βᵀ (f_j − f_i), weighted least squares with a small ridge on β, the
//            features f scaled to the window's range, of the render's change to the photo
//            T = C − (1 − α) P (the photo P is exact: it never passes through the filter, so a
//            clipped window or a sharp frame in it cannot blur; what the fit can bias is the change);
//   output   (1 − α_i) P_i + β₀, with β₀ = Σ_j l_j T_j, l_j = w_ij uᵀ x_j and u = A⁻¹ e₀ (A the
//            normal matrix): a linear smoother, whose variance Σ_j l_j² v_j is the estimate's own
//            (`variance`, in the guide's units).
// The features: the albedo, the shading normal, the depth, the objects' coverage and the photo's
// luminance behind them (the noise-free texture the catcher's change modulates).
//
// Large images are fitted over blocks. With blocks of s × s pixels (DenoiseSettings::block; by
// default the image's short side over 480, so 1 at 640 × 480 and 3 at 1920 × 1440), the fit is
// made over a window of (2R + 1)² blocks, each the mean of its pixels' change, guide and features,
// and each pixel i of block c takes the fit at its own features:
//   T̂_i = β₀ + βᵀ (f_i − f_c)
// so its texture, normal and edge within the block stay its own (output/denoise_inputs.h). The
// window then covers the same share of the image and of the objects at every size, and each of
// its taps averages s² pixels: the noise falls as it does at 640 × 480 with s² times the samples,
// for the same cost, the fit being shared by the block's pixels. What a block gives up is an
// edge no feature sees (a shadow's) within its s pixels. The variance stated is the block's β₀'s.
//
// The pixels estimated are those the render touched (composite.h's touched_mask) and those within
// 2 pixels of them: all the samples of a pixel beside a faint change may have missed it, and its
// own variance, 0, does not say it is exact (it takes its neighbours'). Every other pixel is
// returned as it came, bit for bit, and takes part in its neighbours' fits as an exact value
// (v = 0).
#pragma once
#include <cstddef>

#include "core/image.h"
#include "render/render.h"

namespace insitu {

struct DenoiseSettings {
  int radius = 6;       // R: the window is (2R + 1)² pixels
  double k = 0.45;      // Rousselle et al. 2012's colour tolerance in standard errors
  double ridge = 1e-3;  // of the window's total weight, on each scaled feature's coefficient
  int block = 0;        // s: the fit's taps are blocks of s × s pixels (0: by the image's size)
};

struct Denoised {
  Image composite;  // RGB, linear
  int block = 1;    // s: the fit's taps were blocks of s × s pixels
  // With blocks: the estimated pixels of the blocks whose fit does not serve them
  // (denoise_edges.h), each fitted over its own window.
  std::size_t pixels_fitted_alone = 0;
  Image variance;   // 1 channel: the variance of the denoised luminance (0 where not estimated)
  Image estimated;  // 1 channel: 1 where the composite is the denoiser's estimate, 0 where it is the input's
};

// `composite_linear` is composite()'s, `variance` composite_variance()'s (1 channel).
Denoised denoise_composite(const Image& photo_linear, const Image& composite_linear, const Image& variance,
                           const RenderLayers& layers, const DenoiseSettings& settings = {});

// The slow reference: the same fit by an explicit weighted least-squares solve (Eigen's
// column-pivoting QR of √W X) over the pixel's block's window, each weight from its own patch
// distance; one pixel. For the tests.
Rgb denoise_pixel_reference(const Image& photo_linear, const Image& composite_linear, const Image& variance,
                            const RenderLayers& layers, const DenoiseSettings& settings, int x, int y);

}  // namespace insitu
