// Inverse lighting's fit of the clipped sources' scales (relight/inverse_lighting.h): how each
// source is fitted, from its parts free to its parts pooled, whole, tied with the others, or left
// at the lower bound, each judged by how well the photo determines the light it adds.
#pragma once
#include <atomic>
#include <vector>

#include "relight/inverse_lighting.h"
#include "relight/inverse_lighting_pixels.h"
#include "relight/inverse_lighting_solve.h"

namespace insitu::inverse_lighting_detail {

// Fits the free sources' parts, each source judged by the σ of its added power (the sum over its
// parts: determined even where its parts are not told apart). A source so undetermined has the
// parts the photo says nothing of held at the lower bound, or those it does not tell apart pooled
// (take_out_unknown_parts), and is fitted again; one still
// undetermined is fitted whole, one scale for all its parts (where the photo gives only the
// irradiance its parts add together, not their power). The still undetermined ones are fitted
// again as one (the most efficient of them): if the photo determines that, it says how much light
// is missing (InverseLightingResult::missing_irradiance), not from where; they stay at the lower
// bound.
// `warm`: each fit starts from the parts' current scales (a column's mean a), not from the lower
// bound.
void fit_sources(const std::vector<FitPixel>& pixels, const Albedos& albedos, InverseLightingResult& res,
                 const std::atomic<bool>* stop, bool warm = false);

// Whether a fit on finer parts is kept over the coarse fit it refines. The fine parts nest the
// coarse ones (equal scales within a cut part give the coarse fit, up to the estimates' noise), so
// a fine fit that explains the photo worse, its robust residual past kFineResidualTolerance × the
// coarse one's, has run off (the sun unseen from the capture point: ×500 lamps, residual 2.5× the
// coarse one's); nor is one kept that leaves a source undetermined that the coarse fit determined
// (more unknowns: the closed room's window at one offset of the grid went to the lower bound).
constexpr double kFineResidualTolerance = 1.1;
bool keep_finer_fit(const InverseLightingResult& coarse, const InverseLightingResult& fine);

}  // namespace insitu::inverse_lighting_detail
