// A mesh handed over in memory (the C API's insitu_mesh, the Python module's numpy arrays) rather
// than read from an OBJ file: the same checks as the OBJ reader, each naming the array and index.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "render/mesh.h"

namespace insitu {

struct MeshArrays {
  const float* positions = nullptr;  // 3 per vertex, object frame, metres
  std::size_t vertex_count = 0;
  const float* normals = nullptr;          // 3 per vertex, or null: the geometric normal
  const float* uvs = nullptr;              // 2 per vertex, or null
  const std::uint32_t* indices = nullptr;  // 3 per triangle, into the vertices
  std::size_t triangle_count = 0;
  // One material for the whole mesh (mesh.h Material): linear Kd, Ks, Phong Ns, and an optional
  // linear RGB texture (3 floats per texel, rows top to bottom) that multiplies Kd.
  Rgb kd = Rgb(0.8f, 0.8f, 0.8f), ks = Rgb::Zero();
  float ns = 0;
  const float* map_kd = nullptr;
  int map_kd_width = 0, map_kd_height = 0;
};

// Throws InputError("name: indices[7]", ...) for non-finite values, indices out of range, a
// texture with no texels or without UVs to sample it, negative reflectances, and a mesh left with
// no triangles; degenerate triangles are dropped and counted in a warning, as for OBJ files.
Mesh mesh_from_arrays(const MeshArrays& arrays, const std::string& name, Warnings& warnings);

}  // namespace insitu
