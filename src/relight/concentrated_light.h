// Inverse lighting's coarse-to-fine step (relight/inverse_lighting.h): a part the coarse fit puts
// far brighter than the rest of its source holds a concentrated light (the sun in a window's sky, a
// lamp's bulb), which is placed at the one fit texel that explains the photo best, with a ring of
// the texels around it free to take what of it spilled into them.
#pragma once
#include <vector>

#include "relight/inverse_lighting.h"
#include "relight/inverse_lighting_pixels.h"
#include "relight/inverse_lighting_solve.h"

namespace insitu::inverse_lighting_detail {

// A part at kConcentrated × its source's scale or more is cut (see concentrated_light.cpp for the
// measurements behind both numbers); at most kMaxFineParts fit texels are cut in all, each an
// irradiance estimate (a RoomLight of the cube's size) at every pixel.
inline constexpr double kConcentrated = 3.0;
inline constexpr std::size_t kMaxFineParts = 128;
// A point's ring: the cut texels whose direction lies within kRingPitches texel pitches (the angle
// of a face-centre texel, (π/2)/n) of the point's: the eight around it (concentrated_light.cpp).
inline constexpr double kRingPitches = 1.5;

// The log-residual cost of a point of added scale `a` on the texel whose irradiance at each pixel
// is `column`, over `base` (every other part at its scale): Σ log(1 + ((r − r̄_s)/0.1)²), r the
// pixel's log P − log E and r̄_s its surface's mean r (the least-squares log albedo). The Cauchy
// loss of the fit itself (inverse_lighting_solve.h) with the albedos solved in closed form.
double point_cost(const std::vector<FitPixel>& pixels, const std::vector<double>& base,
                  const std::vector<double>& column, double a, int surfaces);

// Among the parts `group` of res.parts (one source's cut texels, at their coarse scales), the one
// whose point explains the photo best, and its added scale a (the point's scale is 1 + a): each
// texel's a minimises point_cost over [a₀/100, 10 a₀], a₀ putting the group's whole added power
// (Σ (s − 1) power) on it, by golden-section search in log a. a is 0 where no point explains the
// photo better than none.
std::pair<std::size_t, double> best_point(const std::vector<FitPixel>& pixels, const InverseLightingResult& res,
                                          const std::vector<std::size_t>& group, int surfaces);

// Cuts the concentrated parts, gathers each source's cut texels into a point, its ring and the rest, and
// fits the sources again from there. Returns whether that fit was kept (keep_finer_fit); where it
// is not, `pixels` and `res` are the coarse fit's. `shares`: the box's opening shares at the
// cube's size (RoomLight::opening_shares).
bool refine_concentrated_parts(std::vector<FitPixel>& pixels, const Albedos& albedos, const InverseLightingInput& in,
                               const std::vector<float>& shares, InverseLightingResult& res);

}  // namespace insitu::inverse_lighting_detail
