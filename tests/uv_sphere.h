// A UV sphere as glTF buffers: `rings` × `segments` quads (the poles' rows as triangles), smooth
// normals, glTF UVs (v down), uint32 indices; and as a Mesh. For the glTF and tangent tests
// (gltf_fixture.h, tangents_test.cpp) and the glTF benchmarks (bench/gltf_bench.cpp); no test
// framework needed.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "render/mesh.h"

namespace insitu::test {

struct UvSphere {
  std::vector<float> pos, nor, uv;  // 3, 3 and 2 per vertex
  std::vector<std::uint32_t> idx;   // 2 · segments · (rings − 1) triangles
};

inline UvSphere make_uv_sphere(int rings, int segments, const float centre[3], float radius) {
  UvSphere s;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j <= segments; ++j) {
      const double theta = pi * i / rings, phi = 2 * pi * j / segments;
      const double n[3] = {std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)};
      for (int k = 0; k < 3; ++k) s.pos.push_back(float(centre[k] + radius * n[k])), s.nor.push_back(float(n[k]));
      s.uv.push_back(float(j) / float(segments)), s.uv.push_back(float(i) / float(rings));
    }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const std::uint32_t a = std::uint32_t(i * (segments + 1) + j), b = a + std::uint32_t(segments + 1);
      if (i > 0) s.idx.insert(s.idx.end(), {a, b, a + 1});
      if (i < rings - 1) s.idx.insert(s.idx.end(), {a + 1, b, b + 1});
    }
  return s;
}

// The sphere as a Mesh: every corner indexes its vertex's position, normal and UV (OBJ's v up).
inline Mesh uv_sphere_mesh(const UvSphere& s) {
  Mesh m;
  for (std::size_t i = 0; i < s.pos.size() / 3; ++i) {
    m.positions.emplace_back(s.pos[3 * i], s.pos[3 * i + 1], s.pos[3 * i + 2]);
    m.normals.emplace_back(s.nor[3 * i], s.nor[3 * i + 1], s.nor[3 * i + 2]);
    m.uvs.emplace_back(s.uv[2 * i], 1.0f - s.uv[2 * i + 1]);
  }
  for (std::size_t i = 0; i < s.idx.size(); i += 3) {
    Triangle t{};
    for (std::size_t k = 0; k < 3; ++k) t.v[k] = s.idx[i + k], t.n[k] = t.t[k] = std::int32_t(s.idx[i + k]);
    m.triangles.push_back(t);
  }
  return m;
}

}  // namespace insitu::test
