#include "render/cutouts.h"

#include <algorithm>
#include <cstring>

#include "core/sampler.h"
#include "render/embree_scene.h"

namespace insitu {
namespace {

std::uint64_t float_bits(float a, float b) {
  std::uint32_t x = 0, y = 0;
  std::memcpy(&x, &a, 4);
  std::memcpy(&y, &b, 4);
  return (std::uint64_t(y) << 32) | x;
}

// The opacity of candidate hit i of a filter call: 1 where the material is not a cut-out.
struct Candidate {
  unsigned mesh, triangle;
  float opacity;
};
Candidate candidate(const RTCFilterFunctionNArguments* args, unsigned i) {
  const auto* ctx = reinterpret_cast<const CutoutContext*>(args->context);
  const unsigned geom = RTCHitN_geomID(args->hit, args->N, i), prim = RTCHitN_primID(args->hit, args->N, i);
  const Mesh& mesh = (*ctx->meshes)[geom];
  const Triangle& tri = mesh.triangles[prim];
  const Material& mat = mesh.materials[std::size_t(tri.material)];
  if (!mat.cutout()) return {geom, prim, 1.0f};
  return {geom, prim,
          mat.opacity(uv_at(mesh, tri, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i)))};
}

void stochastic_filter(const RTCFilterFunctionNArguments* args) {
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const Candidate c = candidate(args, i);
    if (c.opacity >= 1) continue;
    RTCRayN* r = args->ray;
    const unsigned n = args->N;
    const std::uint64_t h =
        hash4(float_bits(RTCRayN_org_x(r, n, i), RTCRayN_org_y(r, n, i)),
              float_bits(RTCRayN_org_z(r, n, i), RTCRayN_dir_x(r, n, i)),
              float_bits(RTCRayN_dir_y(r, n, i), RTCRayN_dir_z(r, n, i)), (std::uint64_t(c.mesh) << 32) | c.triangle);
    if (!(c.opacity > 0) || hash_to_unit(h) >= c.opacity) args->valid[i] = 0;
  }
}

void sheer_filter(const RTCFilterFunctionNArguments* args) {
  for (unsigned i = 0; i < args->N; ++i)
    if (args->valid[i] == -1 && !(candidate(args, i).opacity > 0)) args->valid[i] = 0;
}

void shadow_filter(const RTCFilterFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<CutoutContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const Candidate c = candidate(args, i);
    if (c.opacity >= 1) continue;
    args->valid[i] = 0;
    if (!(c.opacity > 0)) continue;
    const std::uint64_t key = (std::uint64_t(c.mesh) << 32) | c.triangle;
    if (!ctx->first_crossing(key)) continue;
    ctx->transmittance *= 1 - c.opacity;
  }
}

}  // namespace

bool CutoutContext::first_crossing(std::uint64_t key) {
  const auto in_place = crossed.begin() + crossed_count;
  if (std::find(crossed.begin(), in_place, key) != in_place) return false;
  if (std::find(crossed_more.begin(), crossed_more.end(), key) != crossed_more.end()) return false;
  if (crossed_count < int(crossed.size()))
    crossed[std::size_t(crossed_count++)] = key;
  else
    crossed_more.push_back(key);
  return true;
}

void init_cutout_context(CutoutContext& ctx, const std::vector<Mesh>& meshes, bool cutouts, CutoutQuery query) {
  rtcInitIntersectContext(&ctx.rtc);
  ctx.meshes = &meshes;
  if (!cutouts) return;
  ctx.rtc.filter = query == CutoutQuery::kStochastic ? stochastic_filter
                   : query == CutoutQuery::kSheer    ? sheer_filter
                                                     : shadow_filter;
}

}  // namespace insitu
