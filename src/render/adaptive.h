// Adaptive sampling: with render.noise_target τ the passes go on until every pixel the
// objects change has a relative standard error of at most τ. Each pixel stops on its own, and spp
// is the most any pixel takes. Stopping is judged between passes from the pixels' sums, so the
// image still depends on nothing but (seed, pixel, sample): not on threads or interruptions.
//
// Pixel i after n_i samples has y_k, the luminance of O + W − N per sample (render.h's variance
// layer), and the value v_i = |mean(O + W − N)| + mean(N) that render.h's noise figure uses. Its
// relative standard error is e_i = √(σ̂_i² / n_i) / v_i, and it stops when e_i ≤ τ. The per-sample
// variance s_j² of pixel j, with d_j degrees of freedom, is render/pixel_variance.h's: batch means
// over blocks of 16 samples from 128 samples on, which err high with scrambled Sobol points, but
// by 1.7× where the per-sample estimate erred by 4× (the spread between seeds was 0.24 of it). A
// variance estimated from the pixel's own few samples is optimistic where light is heavy-tailed:
// a pixel whose samples have all missed a small bright path (the sun through a gap, a caustic)
// looks converged. So σ̂_i² is made honest in three ways:
//   1. At least kMinSamples samples (and the first pass) before any pixel is judged.
//   2. Pooling: the mean s̄² of s_j² over the changed pixels j of its 3 × 3 neighbourhood. A pixel
//      sees nearly the light its neighbours see, and the firefly a neighbour met is one it can meet
//      too (Cycles pools its error estimate over a window for the same reason).
//   3. Each estimate is replaced by its upper 95 % confidence bound for a normal population,
//      s² d / χ²_0.05(d) with d its degrees of freedom: d_i for the pixel's own, D = Σ d_j for the
//      pooled mean (×1.24 at 9 × 15, ×2.07 at 15), with the Wilson–Hilferty approximation
//      χ²_p(k) ≈ k (1 − 2/(9k) + z_p √(2/(9k)))³, z_0.05 = −1.645.
//   σ̂_i² = max(own bound, pooled bound): a pixel noisier than its neighbourhood keeps its own.
// (This rule bounded each s_j² with its own d_j before pooling, ×3.2 at 8 batches, which undid most
// of what the batches gained; with the pixel's own estimate unbounded instead, the heavy-tailed
// test below stopped 0.95 % of its pixels beyond 3τ, against 0.29 % with it bounded.)
//
// Unchanged pixels — no coverage, and with and without the objects equal in every sample (their
// sums equal bit for bit) — have s_i² = 0: they stop once judged if their 8 neighbours are
// unchanged too (σ̂_i² = 0), or if no sample saw a catcher (nothing there can change but a sliver
// of an object's edge); beside a changed pixel they go on until its variance says they are done. A pixel that
// an object's effect reaches with probability p per sample is taken for unchanged after n samples
// with probability (1 − p)^n; the bias that leaves, p (1 − p)^n δ for an effect of relative size
// δ, is at most δ / (e n): 2.3 % of a shadow's depth at 16 samples, where its neighbours have not
// already kept it going.
#pragma once
#include <cstdint>
#include <vector>

#include "render/render_state.h"

namespace insitu {

constexpr int kMinAdaptiveSamples = 16;

// The upper 95 % confidence bound of a variance estimated from n samples (n − 1 degrees of
// freedom), as a factor of it.
double variance_upper_bound_factor(int n);

// The relative standard error of pixel i (of a w × h image of folded sums) with the bounds above;
// 0 where σ̂² is 0, infinite where the pixel cannot be judged (noise over a value of 0).
double honest_relative_error(const std::vector<PixelSums>& sums, int w, int h, std::size_t i);

// Marks in `stopped` the pixels not yet stopped that are done: unchanged as above, or of honest
// relative error at most `target`. `sums` are every pixel's sums after a pass.
void stop_converged(const std::vector<PixelSums>& sums, int w, int h, double target,
                    std::vector<std::uint8_t>& stopped);

}  // namespace insitu
