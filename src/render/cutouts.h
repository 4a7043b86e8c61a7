// Cut-out surfaces (glTF's alpha MASK and BLEND, an MTL's `d`: Material::opacity) in Embree's
// traversal: filters on the intersection context, so that each kind of query decides its own way
// (render/embree_scene.h). Every filter lets an opaque surface's hit stand and ignores a surface
// where it is absent (opacity 0, a mask's cut-away texels); they differ on a sheer one, of opacity
// 0 < a < 1:
//   stochastic  a traced ray meets it with probability a, by a hash of the ray, the mesh and the
//               triangle, so that every sample of a pixel decides anew (pbrt-v4's stochastic
//               alpha), and two meshes' triangles of the same index along one ray independently;
//   sheer       the hit stands: the caller weighs the surface by a itself (the path integrator's
//               camera rays, which split between the surface and what lies behind it);
//   shadow      the ray is attenuated by 1 − a and goes on: transmittance Π (1 − a_k) over the
//               sheer surfaces it crosses, as Cycles's transparent shadows
//               (kernel/integrator/shade_shadow.h); the same mean as passing with probability
//               1 − a, without that Bernoulli's noise in every shadow a sheer surface casts.
// Embree may report one triangle more than once along a ray (a spatial-split BVH,
// RTC_BUILD_QUALITY_HIGH, holds it in several leaves): a ray crosses a triangle's plane once, so
// the shadow filter attenuates once per triangle.
#pragma once
#include <embree3/rtcore.h>

#include <array>
#include <cstdint>
#include <vector>

#include "render/mesh.h"

namespace insitu {

struct CutoutContext {
  RTCIntersectContext rtc;  // first: Embree passes its address to the filter
  const std::vector<Mesh>* meshes = nullptr;
  float transmittance = 1;  // the shadow filter's product so far
  // The sheer triangles it has attenuated by, (mesh << 32) | triangle: the first few in place (a
  // shadow ray crosses few), the rest on the heap.
  std::array<std::uint64_t, 8> crossed{};
  int crossed_count = 0;
  std::vector<std::uint64_t> crossed_more;
  // Whether the triangle `key` is crossed for the first time, which then records it.
  bool first_crossing(std::uint64_t key);
};

enum class CutoutQuery { kStochastic, kSheer, kShadow };

// A context for one query over `meshes` (the scene's, by geometry ID); without cut-outs in the
// scene (`cutouts` false) it carries no filter and Embree sees every surface as opaque.
void init_cutout_context(CutoutContext& ctx, const std::vector<Mesh>& meshes, bool cutouts, CutoutQuery query);

}  // namespace insitu
