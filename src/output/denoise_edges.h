// Where a block's fit does not serve its pixels (output/denoise.h): a first-order fit over block
// means, evaluated at each pixel's own features and position, puts the pixels off where the block
// holds an edge (a table leg's outline and the sofa's contact shadow came out in stair steps of 3
// pixels at 1920 × 1440), or where the fit's slopes are not determined by its data (streaks
// along a thin shadow). There its pixels are fitted one by one, as at block size 1.
#pragma once
#include "output/denoise_fit.h"
#include "output/denoise_inputs.h"

namespace insitu::denoise_detail {

// Whether the pixels of block (bx, by) of s × s are fitted one by one, for one of three reasons:
// - an edge of the geometry: a pixel whose normal, depth or coverage departs from the block's
//   mean by more than a quarter of its range over the fit's window. A smooth ramp departs by about
//   1/(2R + 1) = 0.08 of the range, and an albedo's texture is what the linear fit follows, so
//   neither counts;
// - an edge of the light (a shadow's, which no feature sees): the pixels' guides spread about
//   their mean more than their noise explains, χ² = Σ (g_i − ḡ)² / v_i beyond its 99.9th
//   percentile for n − 1 degrees of freedom (Wilson and Hilferty 1931's cube-root approximation,
//   z = 3.09), so that noise alone sends a block in a thousand;
// - too few taps: the window's weights count fewer effective taps, (Σ w)² / Σ w² (Kish's
//   effective sample size), than the fit has unknowns, so that the ridge alone sets its slopes.
//   At the fit's centre (a pixel's own fit) that costs nothing; at a pixel off it, the slopes'
//   noise is the pixel's.
bool fitted_pixel_by_pixel(const Inputs& pixels, const Inputs& blocks, const Fit<kPositionFit>& fit, int s, int bx,
                           int by);

}  // namespace insitu::denoise_detail
