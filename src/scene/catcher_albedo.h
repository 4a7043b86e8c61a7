// One albedo per local-scene surface, as the photo shows it on average: for exporters that take a
// single colour per surface (interop/blender_export.h). insitu's own render reads the photo at every
// pixel instead (render/catcher.h); this is the mean of that same ratio.
//
// At each photo pixel whose camera ray first meets surface k (the photo is of the empty room, so
// the objects hide nothing), Debevec 1998's local-scene albedo under the captured light:
//   ρ(x) = π P(x) / E(n(x)),  E(n) = ∫ L(ω) max(0, n·ω) dω  (the environment's irradiance at n)
// averaged per channel over the surface's pixels and clamped to [0, 0.95]. Pixels clipped in the
// photo (stored value ≥ 0.999 in a display-referred photo) or not finite are left out: they bound
// the albedo from below only. A surface with a given albedo keeps it; one the photo never shows
// keeps 0.5, and says so (pixels = 0).
#pragma once
#include <vector>

#include "scene/pipeline.h"

namespace insitu {

struct CatcherAlbedo {
  Rgb albedo = Rgb::Constant(0.5f);
  std::size_t pixels = 0;   // photo pixels averaged (0: given, or not seen)
  bool from_photo = false;  // estimated here (else given in the scene file, or unseen)
};

// One per entry of scene.spec.local_scene, in order.
std::vector<CatcherAlbedo> catcher_albedos(const LoadedScene& scene);

}  // namespace insitu
