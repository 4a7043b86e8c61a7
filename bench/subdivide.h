// Midpoint subdivision of a mesh, for measuring the kernel on furniture-sized meshes (issue 16):
// each triangle becomes four by its edges' midpoints, positions, normals and UVs alike. The surface
// is the same surface — every new vertex lies on the old triangle's plane, and the shading normal
// and UV interpolate to the same values — so a render of the subdivided mesh is the same image up
// to float rounding, with 4^levels times the triangles for Embree to traverse.
#pragma once
#include "render/mesh.h"

namespace insitu {

Mesh subdivide_midpoint(const Mesh& mesh, int levels);

}  // namespace insitu
