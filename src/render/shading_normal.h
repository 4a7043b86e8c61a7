// The shading normal's two corrections, as Cycles 3.4 makes them: a tangent-space normal map
// (kernel/svm/tex_coord.h, svm_node_normal_map) and the bend that keeps a shading normal's mirror
// direction above the surface (kernel/closure/bsdf_util.h, ensure_valid_reflection).
#pragma once
#include "core/math.h"

namespace insitu {

// The normal a tangent-space map gives, from the unnormalized interpolated normal n and tangent t
// (xyz; w the interpolated bitangent sign) and the texel c (linear, in [0, 1]):
//   m = 2c − 1,   b = t_w · (n × t),   N = normalize(m_x t + m_y b + m_z n).
// Zero where that sum is zero.
Vec3f tangent_space_normal(const Vec3f& n, const Vec4f& t, const Rgb& texel);

// The Normal Map node's strength s ≠ 1: normalize(n_s + s · (N − n_s)), s clamped to ≥ 0; n_s the
// unmapped shading normal (both on the viewer's side).
Vec3f with_strength(const Vec3f& n_s, const Vec3f& mapped, float strength);

// A shading normal n whose mirror reflection of the direction to the viewer, wo, dips below
// min(0.9 (ng · wo), 0.01) over the geometric normal ng is turned toward ng, within the plane of
// ng and n, until the reflection sits at that height; where no such normal exists, ng. All unit
// vectors, ng on the viewer's side. Every Cycles closure gets its normal through this.
Vec3f valid_reflection_normal(const Vec3f& ng, const Vec3f& wo, const Vec3f& n);

}  // namespace insitu
