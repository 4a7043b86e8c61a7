// The robust least-squares fit of inverse lighting (inverse_lighting.h): the photo's pixels of
// real surfaces, P = ρ/π (E0 + Σ_c a_c coef_c), with one unknown a ≥ 0 per column of parts and one
// ρ per surface, in log residuals under a Cauchy loss (Ceres), and the references' known albedos.
#pragma once
#include <Eigen/Core>

#include <atomic>
#include <optional>
#include <vector>

#include "relight/inverse_lighting_pixels.h"

namespace insitu {
namespace inverse_lighting_detail {

// The Cauchy loss's scale on the log residuals: 10 % off is where a pixel starts to count less
// (texture, furniture left in the room, a window frame: inverse_lighting.h).
inline constexpr double kCauchyScale = 0.1;

// The unknowns' columns: each a set of parts that share one a (a free source's part alone, a
// source's parts fitted whole, or the most efficient tied source's parts: make_columns).
// coef(p, c) = Σ_{j ∈ c} E_j(p).
using Columns = std::vector<std::vector<int>>;

// What the fit knows of each surface's albedo.
struct Albedos {
  std::vector<double> log_rho;              // start values; fixed where known
  std::vector<bool> known;                  // uniform and given (a plane's albedo)
  std::vector<std::optional<double>> mean;  // a reference mean albedo
  std::vector<bool> reference;              // a reference in the photo (a sheet, a ball)
  int surfaces = 0, references = 0;
};

// The unknown ρ start at π · median(P/E0) of their surface; known ones at their value.
Albedos initial_albedos(const std::vector<FitPixel>& pixels, const InverseLightingInput& in);

struct Fit {
  std::vector<double> a;  // per column
  std::vector<double> log_rho;
  Eigen::MatrixXd jtj;            // JᵀJ (robust weights) over the columns' a, then the free ρ
  double sigma_r = 0;             // robust scale of the log residuals
  std::vector<double> residuals;  // per pixel, unweighted
  bool referenced = false;        // a reference of known albedo was in the fit
};

// The fit: robust, from a = 0 (every source at its lower bound). Where a reference is in the photo
// it fits only the informative pixels, and starts instead from the convex fit of the known-albedo
// pixels (convex_start), then a fit with a Cauchy loss of scale 1, nearly least squares in log
// (graduated non-convexity, Black & Rangarajan 1996): from the lower bound a key light's pixels
// are all 50 % or more off, in the narrow loss's flat tail, where the solver stopped far short (a
// grey ball's residuals at 22 % where a least-squares fit of the same parts leaves 3.5 %). It is
// then fitted again with the reference's residuals weighed by their own scale. The room's surfaces
// share one σ: their residuals are mostly texture, an albedo that varies over the surface, which
// is not independent noise and must not count as precision (with a σ per surface the closed
// room's error with JPEG shots went from 8 % to 34 %). A reference's albedo is uniform and
// known, so its residuals are noise and the model's error: a grey ball's 2–3 % must weigh as such
// beside a checkered floor's 50 %. Without a reference the closed room keeps the fit from the
// lower bound: there the start at least squares finds a lower cost further from the truth (the
// window's added power 7.6 against the true 3.65, the error 20 % against 8 %), a bias of the
// room's model not yet explained. `a_start`, where given, is the start of that fit without a
// reference instead of a = 0 (the coarse-to-fine refinement starts from the coarse fit's scales).
//
// With a reference, the fit smooths within each source (`column_source`: the source of each column
// that is one part alone, −1 for any other): residuals √(λN) (log(1 + a_c) − the mean of
// log(1 + a) over the single parts of c's source), N the fit's pixels, λ = kReferenceSmoothing.
// JᵀJ and σ stay the data's alone.
//
// `stop` (core/stop.h) ends the solver at its next iteration, and solve throws Stopped.
Fit solve(const std::vector<FitPixel>& all_pixels, const Columns& columns, const Albedos& albedos,
          const std::atomic<bool>* stop, const std::vector<double>* a_start = nullptr,
          const std::vector<int>* column_source = nullptr);

// The smoothing's weight in a fit with a reference: the prior weighs as much as N pixels at a log
// residual of √λ (0.45 %). Made for open ground, where the floor sees every direction alike and
// leaves the fit, and the reference alone — a matt ball, whose shading is the light through a
// clamped cosine, about nine numbers (Ramamoorthi & Hanrahan 2001) — cannot tell one part of a
// window from its neighbour a few degrees away. The free fit then picks a point along directions
// the data leaves flat; the smoothing picks, among them, the parts that share their source's scale,
// and leaves the source's total to the photo. It applies to every fit with a reference, in a room
// box too, where the walls tell the parts apart and the data outweigh it: a white sheet in the
// synthetic sun room (InverseLighting.ASheetInARoomLeavesTheSunsPartToThePhoto) gives the sun's
// part 1.51 of a true 1.68 with it, 1.40 without. No Cycles room with a reference measures it yet.
// Without a reference there is none: the closed room's photo places the sun's texel at × 18 000
// inside a sky at × 100, and smoothing pulled the sun back toward the sky (8.2 % to 15.8 % at
// λ = 10⁻⁶). docs/validation.md, "Priors on the parts".
inline constexpr double kReferenceSmoothing = 2e-5;

}  // namespace inverse_lighting_detail
}  // namespace insitu
