// Inverse lighting against the photo (Marschner & Greenberg 1997, Karsch et al. 2011):
// the strength of the sources that clipped in the shots (clipped_sources.h), from what the photo
// shows they do to the room's real surfaces.
//
// Model. A photo pixel i that sees a real surface — a plane of the local scene, or a wall, the
// floor or the ceiling of the room box — at x_i with normal n_i (toward the camera) shows
//   P_i = ρ_s(i)/π · E(x_i),   E(x_i) = E_0(x_i) + Σ_k a_k E_k(x_i),   a_k = s_k − 1 ≥ 0,
// since E is linear in the cube: E_0 is the irradiance of the cube as assembled (every source at
// its lower bound), E_k that of source k's texels alone. Both are the renderer's own estimate
// (PlaneIrradiance::estimate through the room light: the box's parallax and its openings), so
// the fitted cube is what the render then uses. ρ_s is one albedo per surface, a nuisance unknown,
// or known: a plane of the local scene with a given albedo is a reference (white paper ≈ 0.8, a
// grey card 0.18, "the floor's mean albedo is 0.5") that fixes its surface's ρ.
//
// Fit. On luminance, with log residuals r_i = log P_i − log(ρ_s(i)/π · E_i) (the error that
// matters is relative), a Cauchy loss of scale 0.1 (texture, furniture left in the room, a
// window frame), Ceres, a_k ≥ 0. Left out: pixels clipped in the photo, pixels darker than 1 % of
// the median (noise), pixels through an opening (outside), and pixels whose E_0 is 0.
//
// Identifiability. s_k is determined only where source k's share of E varies across the pixels
// of a surface whose ρ is unknown, or where a surface's ρ is known. Under distant light over an
// open plane E_k/E_0 is the same at every pixel and a_k trades exactly against ρ. The fit's
// covariance (ceres::Covariance: (JᵀJ)⁻¹ scaled by the residuals' variance) says which: a source
// whose σ(s_k) exceeds s_k / 2 (infinite where the data say nothing) is not determined and stays
// at its lower bound. The undetermined ones are then fitted once more as one unknown (all added
// light given to the one that reaches the photo's surfaces best: the least light that explains
// the photo). Over an open plane with a reference that is all the photo gives — the floor's
// irradiance, one number — and it says how much light is missing, not from where: that is
// reported (missing_irradiance), not applied. (On the open-ground validation scene, giving the
// missing light to the most efficient source made the objects 1.7× too bright, and one scale for
// every clipped texel 2.5×, against 0.67× at the lower bound: the direction matters more than the
// amount.)
//
// Parts. A clipped window holds the sky and the sun, whose true radiances differ by orders of
// magnitude: each source is cut into parts of about (n/16)² texels, each with its own a ≥ 0, and
// judged by the σ of its total added power (its parts need not be told apart). Clipped regions
// closer than a part's width are one source (the fit resolves nothing finer): alone, a speck
// beside a window's edge — JPEG ringing, texture at the clip level — was free to take what the
// fit left (docs/validation.md, "A raised ball"). A source whose total is undetermined first holds
// at the lower bound the parts the photo says nothing of (a speck out of its view), then pools,
// one scale for them, the parts it does not tell apart (the sky of a window around its sun),
// keeping free those it does (the sun's, by its patch), and only if that is all or none of them
// is fitted whole (inverse_lighting_sources.h).
// Coarse to fine: a part fitted far brighter than its source (the sun in a window's sky) is then
// cut into its texels, and the source's concentrated light put on the one texel whose point
// explains the photo best, the rest of the cut texels one part; the sources are fitted again, so
// that the photo, not the grid, places it. A fine fit that explains the photo worse than the
// coarse one (its residual 1.1× or more) has run off and is not kept (concentrated_light.h;
// docs/validation.md, "Where the part grid falls", "A concentrated light as a point").
//
// Size. The fit sees the cube at most kFitFaceSize texels a face (fit_resolution.h: shrunk, and
// the result mapped back so each part adds the same power to the full cube's clipped texels), and
// builds the parts' lights a few at a time (inverse_lighting_pixels.h, PartLights): its memory is
// bounded whatever the shots' size and however many specks clipped, and so is its time, with the
// photo's pixels (max_pixels on a grid) and the parts (make_parts: about 48).
//
// Colour. A texel that clipped in all three channels kept no colour (white at the clip level),
// but a warm bulb's light is orange on the walls it lights. With the parts' scales fixed at the
// luminance fit's, each channel is fitted as the luminance was, one multiplier m_k,c per
// determined source (its parts at their fitted ratios) and one ρ per surface and channel: the same
// identifiability per channel. The added light's colour is m_k / Y(m_k), so the luminance fit's
// energy stays; it is applied where every channel's σ ≤ 0.1 of Y(m_k) and it departs from white
// by more than max(3σ, 0.1) in some channel (a smaller cast is within the model's own biases).
//
// A grey ball (FitReference::ball: its centre and radius in the world) is a reference that sees
// the light from every side the camera sees of it: its pixels (those wholly on it) are surface
// points of known ρ with as many normals, P_i = ρ/π E(x_i, n_i), E over the normal's whole
// hemisphere — below the horizon the floor as the shots saw it — estimated pixel by pixel. Over
// an open plane, where the floor's irradiance is one number, the ball tells an overhead lamp from
// a window at the side — but only broadly: a matt convex object's shading keeps the light's first
// nine spherical-harmonic coefficients (Ramamoorthi & Hanrahan 2001), and allocations of the
// missing light with the same nine shade it alike. Its shadow tells where a light is: under
// distant light the floor pixels from 2 to 8 radii of its centre are fitted with it
// (inverse_lighting_pixels.h, shade_by_balls), with an albedo of their own; those it hides, or
// within 2 radii (its reflection onto the floor is not modelled), are left out, and in a room box
// all within 4 radii. With a reference the fit leaves out the pixels that cannot inform the light
// (a surface of unknown albedo whose pixels all see one E), starts from the convex fit of the
// known-albedo pixels and then a near-least-squares one, weighs the reference's residuals by their
// own scale, and takes the parts it holds at 0 as known (solve, unpinned). It also pulls each
// part's log scale gently toward its source's mean (kReferenceSmoothing): where a ball cannot tell
// one part of a window from its neighbour they share the window's scale, and where the data can,
// each keeps its own (docs/validation.md, "Smoothing in fits with a reference"). A ball on a plate
// of its own: its shadow zone's pixels are the plate's over the clean photo's, which cancels the
// floor's texture (inverse_lighting_pixels.cpp, divide_by_clean_photo).
//
// Under distant light the clipped texels that look into a plane of the local scene show the
// ground, not light, and are no source (light_texels).
//
// A reference of known mean albedo ρ̄ adds one residual, log(mean_i π P_i / E_i) − log ρ̄ over its
// pixels, weighted as known to 1 %. A reference in the photo (FitReference: a white sheet, a grey
// card, drawn as a polygon) is a surface of its own with ρ known: its pixels, sampled more densely
// than the rest (it is small), leave the surface they lie on and fix the scale through
// P_i = ρ/π E(x_i) at the geometry they see (the plane or wall under the sheet).
#pragma once
#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "relight/clipped_sources.h"
#include "light/room_light.h"

namespace insitu {

// A plane of the local scene, as the fit sees it.
struct FitPlane {
  Vec3f point = Vec3f::Zero(), normal = Vec3f(0, 1, 0);
  std::optional<float> albedo;       // known and uniform (a white sheet): fixes ρ of this surface
  std::optional<float> mean_albedo;  // known on average over its pixels ("the floor's mean is 0.5")
};

// A ball in the room (world frame, metres).
struct FitBall {
  Vec3f center = Vec3f::Zero();
  float radius = 0;
};

// Something of known uniform albedo in the photo: a patch (a white sheet ≈ 0.8, a grey card 0.18),
// a polygon in photo pixels (DESIGN.md's pixel convention) on a real surface of the fit; or a grey
// ball, when `ball` is set (the polygon then unused).
struct FitReference {
  std::vector<Vec2d> polygon_px;
  float albedo = 0.8f;  // luminance
  std::optional<FitBall> ball;
  // A reference plate: the same view with the reference in it, linear, and its clipped mask; its
  // pixels are read from it, and the photo's need not avoid the reference. Null: the photo.
  const Image* plate_linear = nullptr;
  const Image* plate_clipped = nullptr;
};

// What the fit made of a reference: the photo pixels it sampled inside the polygon, those left out
// because the photo clipped there, those on no real surface (an opening, the sky), and those used.
struct ReferenceUse {
  int sampled = 0, clipped = 0, off_surface = 0, used = 0;
  int shadow = 0;  // a ball's: pixels of the surface around it fitted with its shadow
};

struct InverseLightingInput {
  const CubeMap* radiance = nullptr;  // as assembled
  const CubeMap* clipped = nullptr;   // EnvironmentInfo::clipped_cube
  std::optional<RoomBox> room;
  const Camera* camera = nullptr;
  const Image* photo_linear = nullptr;
  const Image* photo_clipped = nullptr;  // clipped_mask of the photo (may be null)
  std::vector<FitPlane> planes;
  std::vector<FitReference> references;
  int max_pixels = 2000;                    // photo pixels used, on a regular grid
  int reference_pixels = 256;               // per reference, on its own finer grid
  int samples = 128;                        // per estimate of E0
  int part_samples = 64;                    // per estimate of a part's E (drawn on its few texels)
  const std::atomic<bool>* stop = nullptr;  // core/stop.h: throws Stopped once set
};

struct SourceFit {
  ClippedSource source;
  double scale = 1, sigma = 0;  // s_k and its standard deviation; 1 and 0 when undetermined
  bool determined = false;
  double added_power = 0;  // (s_k − 1) · power
  // The colour of the added light relative to the clipped value's, luminance 1, and the fit's σ
  // per channel (0: not fitted). Determined where each σ ≤ 0.1; applied where it also departs
  // from 1 by more than max(3σ, 0.1) in a channel (fit_colours); otherwise the added light keeps
  // the clipped colour.
  Rgb colour = Rgb::Ones(), colour_sigma = Rgb::Zero();
  bool colour_determined = false, colour_applied = false;
};

// A part of a source (split_into_parts): the unit that gets its own scale.
struct PartFit {
  ClippedSource texels;
  int source = 0;
  double scale = 1;
};

struct InverseLightingResult {
  std::vector<SourceFit> sources;
  std::vector<PartFit> parts;
  int pixels = 0;  // photo pixels in the fit
  int surfaces = 0, reference_surfaces = 0;
  std::vector<ReferenceUse> references;  // per FitReference, in order
  double clipped_power_share = 0;        // of the cube's power, at the lower bound
  double cube_power = 0;                 // Σ Y ΔΩ of the cube as assembled
  // The light the undetermined sources add to the photo's surfaces, as a share of what they get
  // at the lower bound, when the photo determines that much (empty otherwise).
  std::optional<double> missing_irradiance;
  double residual_rms = 0;  // of the log residuals (robust fit's final)
  int fit_face_size = 0;    // the cube's face as the fit saw it (fit_resolution.h)
  std::string status;       // "none" (nothing clipped), "fitted", "partly", "undetermined"
  std::string message;      // one sentence for the user
  bool any_determined() const;
  CubeMap apply(const CubeMap& radiance) const;  // parts multiplied by their scales, in their colour
};

InverseLightingResult recover_clipped_sources(const InverseLightingInput& in);

}  // namespace insitu
