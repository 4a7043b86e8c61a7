// The photo pixels inverse lighting fits (inverse_lighting.h), and the irradiance at each: which
// pixels see a real surface (a local-scene plane, the room box's faces, a reference's patch or
// ball) and are neither clipped nor dark, where they see it and with which normal; and E0 and
// each part's Ek there, by the renderer's own estimator.
#pragma once
#include <functional>
#include <memory>
#include <vector>

#include "relight/inverse_lighting.h"

namespace insitu {
namespace inverse_lighting_detail {

// A photo pixel that sees a real surface, with the irradiance there of the cube (E0) and of each
// source alone (Ek).
struct FitPixel {
  Vec3f x = Vec3f::Zero(), n = Vec3f::Zero();
  int surface = 0;
  bool on_ball = false;  // a reference ball's: E differs at every pixel, with the normal
  int shadow_ball = -1;  // the reference ball in whose shadow zone it lies (shade_by_balls)
  double log_p = 0;
  double e0 = 0;
  std::vector<double> ek;
  // The same per channel, for the sources' colour (fit_colours): P, E0 and each Ek in RGB.
  Rgb p_rgb = Rgb::Zero(), e0_rgb = Rgb::Zero();
  std::vector<Rgb> ek_rgb;
};

// Photo pixels on a regular grid that see a real surface and are neither clipped nor dark
// (outside the references and the balls' reach), and the references' own; `uses` counts each
// reference's pixels.
std::vector<FitPixel> gather_pixels(const InverseLightingInput& in, const RoomLight& room,
                                    std::vector<ReferenceUse>& uses);

// The parts' lights (each part's texels alone), built only while their irradiance is estimated,
// a few at a time: what bounds the fit's memory, however many parts there are.
struct PartLights {
  std::size_t count = 0;
  std::function<std::unique_ptr<RoomLight>(std::size_t part)> make;
};

// E0 and every Ek at each pixel; pixels whose E0 is 0 dropped.
void estimate_irradiance(std::vector<FitPixel>& pixels, const RoomLight& room0, const PartLights& parts,
                         const InverseLightingInput& in);

// Each pixel's Ek of the parts in `replaced` (ascending) dropped, and those of `lights` appended,
// estimated as estimate_irradiance does; E0 keeps E_rest + Σ Ek. `key` sets the new estimates'
// random streams apart from the first ones.
void replace_part_estimates(std::vector<FitPixel>& pixels, const std::vector<int>& replaced, const PartLights& lights,
                            const InverseLightingInput& in, std::uint64_t key);

// Each reference ball pixel's E0 with the floor it sees below it read from the photo (or its
// plate) where the photo shows it, instead of from the cube's lower half (`rest`: without the
// clipped texels).
void light_balls_from_the_floor(std::vector<FitPixel>& pixels, const CubeMap& rest, const InverseLightingInput& in);

// Under distant light, the E0 and Ek of each pixel in a ball's shadow zone (shadow_ball; its surface
// planes + 6 + references + the ball's index where the plane's albedo is unknown) less what the
// ball takes from it (`rest` the cube without the
// clipped texels, `parts` each part's texels of `radiance`); pixels whose E0 is then 0 dropped.
void shade_by_balls(std::vector<FitPixel>& pixels, const CubeMap& rest, const CubeMap& radiance,
                    const std::vector<const ClippedSource*>& parts, const InverseLightingInput& in);

}  // namespace inverse_lighting_detail
}  // namespace insitu
