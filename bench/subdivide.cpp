#include "subdivide.h"

namespace insitu {
namespace {

// Appends (a + b) / 2 of `values` to it and returns its index; -1 where either end is missing.
template <class V>
std::int32_t midpoint(std::vector<V>& values, std::int32_t a, std::int32_t b) {
  if (a < 0 || b < 0) return -1;
  const V m = 0.5f * (values[std::size_t(a)] + values[std::size_t(b)]);  // symmetric in a, b: watertight
  values.push_back(m);
  return std::int32_t(values.size() - 1);
}

// One level: corners 0, 1, 2 and midpoints m01, m12, m20 make four triangles with the old winding.
Mesh subdivide_once(const Mesh& mesh) {
  Mesh out = mesh;
  out.triangles.clear();
  out.triangles.reserve(4 * mesh.triangles.size());
  for (const Triangle& tri : mesh.triangles) {
    std::array<std::uint32_t, 3> mv;
    std::array<std::int32_t, 3> mn, mt;
    for (int e = 0; e < 3; ++e) {
      const int a = e, b = (e + 1) % 3;
      mv[e] = std::uint32_t(midpoint(out.positions, std::int32_t(tri.v[a]), std::int32_t(tri.v[b])));
      mn[e] = midpoint(out.normals, tri.n[a], tri.n[b]);
      mt[e] = midpoint(out.uvs, tri.t[a], tri.t[b]);
    }
    const auto corner = [&](int k) {
      return Triangle{{tri.v[k], mv[k], mv[(k + 2) % 3]},
                      {tri.n[k], mn[k], mn[(k + 2) % 3]},
                      {tri.t[k], mt[k], mt[(k + 2) % 3]},
                      tri.material};
    };
    for (int k = 0; k < 3; ++k) out.triangles.push_back(corner(k));
    out.triangles.push_back({{mv[0], mv[1], mv[2]}, {mn[0], mn[1], mn[2]}, {mt[0], mt[1], mt[2]}, tri.material});
  }
  return out;
}

}  // namespace

Mesh subdivide_midpoint(const Mesh& mesh, int levels) {
  Mesh out = mesh;
  for (int i = 0; i < levels; ++i) out = subdivide_once(out);
  return out;
}

}  // namespace insitu
