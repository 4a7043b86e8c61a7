// Adaptive sampling (issue 16): with render.noise_target τ the passes go on until every pixel the
// objects change has a relative standard error of at most τ. Each pixel stops on its own, and spp
// is the most any pixel takes. Stopping is judged between passes from the pixels' sums, so the
// image still depends on nothing but (seed, pixel, sample): not on threads or interruptions.
//
// Pixel i after n_i samples has y_k, the luminance of O + W − N per sample (render.h's variance
// layer), and the value v_i = |mean(O + W − N)| + mean(N) that render.h's noise figure uses. Its
// relative standard error is e_i = √(σ̂_i² / n_i) / v_i, and it stops when e_i ≤ τ. A variance
// estimated from the pixel's own few samples is optimistic where light is heavy-tailed: a pixel
// whose samples have all missed a small bright path (the sun through a gap, a caustic) looks
// converged. So σ̂_i² is made honest in three ways:
//   1. At least kMinSamples samples (and the first pass) before any pixel is judged.
//   2. Each sample variance s_j² is replaced by its upper 95 % confidence bound for a normal
//      population, s_j² (n_j − 1) / χ²_0.05(n_j − 1) (×2.07 at 16 samples, ×1.38 at 64), with the
//      Wilson–Hilferty approximation χ²_p(k) ≈ k (1 − 2/(9k) + z_p √(2/(9k)))³, z_0.05 = −1.645.
//   3. σ̂_i² = max(s_i², mean of s_j² over the changed pixels j of its 3 × 3 neighbourhood), both
//      bounded as in 2: a pixel sees nearly the light its neighbours see, and the firefly a
//      neighbour met is one it can meet too (Cycles pools its error estimate over a window for the
//      same reason).
// The variance of the mean treats the samples as independent; they are scrambled Sobol points
// (core/sampler.h), whose error falls faster, which makes it conservative too: the spread between
// seeds is about 0.28 of it in the variance layer's test, so pixels stop later than they need to.
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

// The upper 95 % confidence bound of a variance estimated from n samples, as a factor of it.
double variance_upper_bound_factor(int n);

// The relative standard error of pixel i (of a w × h image of folded sums) with the bounds above;
// 0 where σ̂² is 0, infinite where the pixel cannot be judged (noise over a value of 0).
double honest_relative_error(const std::vector<PixelSums>& sums, int w, int h, std::size_t i);

// Marks in `stopped` the pixels not yet stopped that are done: unchanged as above, or of honest
// relative error at most `target`. `sums` are every pixel's sums after a pass.
void stop_converged(const std::vector<PixelSums>& sums, int w, int h, double target, std::vector<std::uint8_t>& stopped);

}  // namespace insitu
