// Inverse lighting at a bounded resolution (inverse_lighting.h). The fit's cost is per part: a
// RoomLight of the cube's size (about 110 bytes a texel with openings: 690 MB at a 1024 face,
// which six 12-megapixel shots give), and an irradiance estimate at every photo pixel. What it
// compares with the photo is irradiance, which a 0.7° texel (a 128 face) resolves as well as a
// finer one. So the fit sees the cube shrunk to at most kFitFaceSize texels a face:
//   L_c = Σ_t L_t ΔΩ_t / Σ_t ΔΩ_t   over the full-resolution texels t whose centre lies in coarse
//                                   texel c (its power kept);
//   clipped_c = max_t clipped_t     (a sun that clipped in one texel stays a source).
// The result is then mapped back (map_to_full_resolution): the light a part adds,
// (s − 1) P_coarse, goes to the full-resolution texels of its coarse texels that clipped,
//   s_full = 1 + (s − 1) P_coarse / P_clipped,
// so the texels that did not clip keep their measured radiance, the added light sits where the
// shots clipped, and its energy is the fit's.
#pragma once
#include "light/cubemap.h"
#include "relight/inverse_lighting.h"

namespace insitu {

constexpr int kFitFaceSize = 128;

struct FitCubes {
  CubeMap radiance, clipped;
};

// The cubes shrunk to a face of min(n, max_face) texels as above.
FitCubes shrink_for_fit(const CubeMap& radiance, const CubeMap& clipped, int max_face = kFitFaceSize);

// The fit's parts and sources (on the shrunk cubes) as texels of the full-resolution ones, their
// scales and σ carried so that each part adds the same power; the powers and shares recomputed.
void map_to_full_resolution(InverseLightingResult& res, const CubeMap& radiance, const CubeMap& clipped);

}  // namespace insitu
