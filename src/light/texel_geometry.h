// Exact geometry of cube-map texels as seen from the cube's centre.
//
// A texel is a square of the face plane (|major axis| = 1); with x = 2s − 1, y = 2t − 1 its solid
// angle is exact (e.g. Driscoll, "Cubemap texel solid angle", 2012):
//   Ω = A(x0, y0) − A(x0, y1) − A(x1, y0) + A(x1, y1),   A(x, y) = atan2(x·y, sqrt(x² + y² + 1)).
//
// Lambert's formula for a polygon P of constant radiance L (Lambert 1760; Arvo 1995): the vector
//   Φ(P) = ½ Σ_edges Θ_j Γ_j,   Θ_j = angle between vertices j and j+1 seen from the origin,
//                                Γ_j = unit normal of the plane through the edge and the origin,
// oriented toward the polygon, gives ∫_P (n·ω) dω = n·Φ(P) for any polygon entirely above the
// horizon of n. A texel that straddles the horizon is first clipped by the plane n·x = 0.
#pragma once
#include <vector>

#include "core/math.h"

namespace insitu {

double texel_solid_angle(int i, int j, int n);
// texel_solid_angle of every texel of a face, row by row (index j·n + i; the same for all six
// faces): the corners' A(x, y) once each, (n + 1)² atan2 instead of 4n².
std::vector<double> face_solid_angles(int n);
// ∫ ω dω over the texel (Lambert's vector); its length is ≤ the solid angle.
Vec3d texel_vector_irradiance(int face, int i, int j, int n);
// Lambert's vector of a planar polygon (vertices in order, any length, not through the origin).
Vec3d polygon_vector_irradiance(const std::vector<Vec3d>& vertices);
// ∫_texel max(0, n·ω) dω exactly: clip the texel to n·x ≥ 0, then Lambert.
double texel_clamped_cosine_integral(int face, int i, int j, int n, const Vec3d& normal);
// The four corners of a texel on its face plane, in order around it.
std::vector<Vec3d> texel_corners(int face, int i, int j, int n);

}  // namespace insitu
