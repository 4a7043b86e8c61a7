// Tangent frames for normal maps: MikkTSpace (Mikkelsen 2008, "Simulation of wrinkled surfaces
// revisited"), the tangent space Blender computes for Cycles's Normal Map node and the one glTF 2.0
// names for files without TANGENT.
//
// For triangles, with Blender's default angular threshold of 180°:
//   1. corners are welded where position, normal and UV are bitwise equal;
//   2. each triangle's tangent is the direction of ∂p/∂u (Mikkelsen's eq. 18), and its
//      orientation the sign of its UV area; a triangle of zero UV area or zero ∂p/∂u "groups with
//      any" and contributes nothing;
//   3. around each welded vertex, the triangles joined through shared edges (consistently wound)
//      and of one orientation form a group; a group-with-any triangle takes the orientation of the
//      first group that reaches it;
//   4. the group's tangent is Σ θᵢ tᵢ normalized, tᵢ the triangle's tangent projected onto the
//      vertex normal's plane and normalized, θᵢ the triangle's angle at the vertex measured between
//      its edges projected onto that plane; its sign is +1 for orientation-preserving groups;
//   5. corners of triangles with two equal positions copy the space of a good corner with the same
//      welded vertex.
// mikktspace.c splits a group further where two tangents differ by more than the threshold; at
// 180° that happens only for exactly opposite tangents, which this leaves joined.
#pragma once
#include <vector>

#include "core/math.h"
#include "render/mesh.h"

namespace insitu {

// One tangent per triangle corner (3 per triangle, in triangle order): xyz unit length in the
// mesh's frame, w = ±1, the bitangent being w · (n × t). UVs come from `uv_set` (0 or 1); a
// corner's normal is its interpolated normal, or the face's where the triangle has none.
std::vector<Vec4f> mikktspace_tangents(const Mesh& mesh, int uv_set);

}  // namespace insitu
