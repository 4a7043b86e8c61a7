// The outside nobody photographed, fitted against the photo. From a point of the room an opening
// shows directions that the capture point c saw as wall (the sky high above a window, seen from
// the floor below it); the room light gives them RoomBox::unseen_outside, or, unknown, the wall c
// saw there, a dim stand-in (room_light.h, "Openings"). With the true light, that stand-in left
// the floor where the window lights it 11–17 % short in two validation rooms (docs/validation.md,
// "Where the objects' brightness goes wrong"), and no fixed fill is right in every room: the sky
// away from what c saw may be brighter or darker.
//
// Model. The unseen outside has the colour and level of what c saw outside, times one unknown
// scale f ≥ 0: L_u = f · u, u = the luminance-median texel of those c saw wholly through an
// opening (a median: the sun in a few texels does not set the sky's level). The irradiance is
// linear in f,
//   E(x_i) = E_w(x_i) + f · E_u(x_i),
// E_w the room light's with the unseen outside black, E_u that of u alone in the unseen
// directions: both by the renderer's estimator, at the photo's pixels on real surfaces, which the
// fit takes as inverse lighting does (inverse_lighting_pixels.h). P_i = ρ_s(i)/π · E(x_i) with
// one unknown albedo per surface; the same robust fit in log residuals (inverse_lighting_solve.h),
// one column, started from f = 1. f is determined where the photo tells the floor near a window
// from the floor far from it: a σ(f) of at most half of max(f, 1) (a level known to within half
// the seen sky's, or to within half its own); otherwise the stand-in stays.
//
// It runs on the light as the shots and inverse lighting leave it (the clipped sources fitted
// first, with the stand-in), at the fit's bounded resolution (fit_resolution.h).
#pragma once
#include <string>

#include "relight/inverse_lighting.h"

namespace insitu {

struct UnseenOutsideFit {
  std::string status;           // "none" (no opening, or c saw nothing through one), "fitted", "undetermined"
  std::string message;          // one sentence for the user
  Rgb unit = Rgb::Zero();       // u: the median of what c saw outside
  double scale = 0, sigma = 0;  // f and σ(f) (σ infinite when the photo says nothing)
  int pixels = 0;
  double light_share = 0;  // of the irradiance at the fit's pixels, mean of f·E_u / E (0 unless fitted)
  // f·u where determined: what RoomBox::unseen_outside takes.
  std::optional<Rgb> radiance() const;
};

// `in.radiance` is the light to complete (its clipped sources fitted already); in.clipped unused.
// Reference balls are left out (their pixels see the floor below them, which the fit of clipped
// light treats apart); a room box with openings is required, else the status is "none".
UnseenOutsideFit fit_unseen_outside(const InverseLightingInput& in);

}  // namespace insitu
