#include "render/mesh_arrays.h"

#include <cmath>
#include <fmt/format.h>
#include <memory>

namespace insitu {

namespace {

// Every value of a float array finite, else the first bad one named.
void check_finite(const float* v, std::size_t n, const std::string& name, const char* array) {
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) throw InputError(fmt::format("{}: {}[{}]", name, array, i), "not a finite number");
}

Material material_of(const MeshArrays& a, const std::string& name) {
  Material m;
  m.name = name;
  for (auto [c, label] : {std::pair{a.kd, "kd"}, std::pair{a.ks, "ks"}})
    if (!c.allFinite() || (c.array() < 0).any())
      throw InputError(name + ": " + label,
                       fmt::format("reflectance ({}, {}, {}) must be finite and ≥ 0", c.x(), c.y(), c.z()));
  if (!std::isfinite(a.ns) || a.ns < 0) throw InputError(name + ": ns", "the Phong exponent must be finite and ≥ 0");
  m.kd = a.kd;
  m.ks = a.ks;
  m.ns = a.ns;
  if (a.map_kd) {
    if (a.map_kd_width < 1 || a.map_kd_height < 1)
      throw InputError(name + ": map_kd", fmt::format("a texture of {}x{} texels", a.map_kd_width, a.map_kd_height));
    if (!a.uvs) throw InputError(name + ": map_kd", "a texture needs UVs to be sampled by");
    Image texture(a.map_kd_width, a.map_kd_height, 3);
    const std::size_t n = texture.data.size();
    check_finite(a.map_kd, n, name, "map_kd");
    texture.data.assign(a.map_kd, a.map_kd + n);
    m.map_kd.image = std::make_shared<const Texels>(std::move(texture));
  }
  return m;
}

}  // namespace

Mesh mesh_from_arrays(const MeshArrays& a, const std::string& name, Warnings& warnings) {
  if (!a.positions || !a.indices || a.vertex_count == 0 || a.triangle_count == 0)
    throw InputError(name, "no triangles: positions and indices must be given and not empty");
  if (a.vertex_count > (std::size_t(1) << 31) || a.triangle_count > (std::size_t(1) << 31))
    throw InputError(name, "more than 2³¹ vertices or triangles");
  check_finite(a.positions, 3 * a.vertex_count, name, "positions");
  if (a.normals) check_finite(a.normals, 3 * a.vertex_count, name, "normals");
  if (a.uvs) check_finite(a.uvs, 2 * a.vertex_count, name, "uvs");
  Mesh mesh;
  mesh.source = name;
  mesh.materials.push_back(material_of(a, name));
  for (std::size_t i = 0; i < a.vertex_count; ++i) {
    mesh.positions.emplace_back(a.positions[3 * i], a.positions[3 * i + 1], a.positions[3 * i + 2]);
    if (a.normals) {
      const Vec3f n(a.normals[3 * i], a.normals[3 * i + 1], a.normals[3 * i + 2]);
      mesh.normals.push_back(n.norm() > 0 ? n.normalized() : n);
    }
    if (a.uvs) mesh.uvs.emplace_back(a.uvs[2 * i], a.uvs[2 * i + 1]);
  }
  std::size_t degenerate = 0;
  for (std::size_t t = 0; t < a.triangle_count; ++t) {
    Triangle tri;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = a.indices[3 * t + std::size_t(c)];
      if (v >= a.vertex_count)
        throw InputError(fmt::format("{}: indices[{}]", name, 3 * t + std::size_t(c)),
                         fmt::format("vertex {} out of range (the mesh has {} vertices)", v, a.vertex_count));
      tri.v[std::size_t(c)] = v;
      tri.n[std::size_t(c)] = a.normals ? std::int32_t(v) : -1;
      tri.t[std::size_t(c)] = a.uvs ? std::int32_t(v) : -1;
    }
    tri.material = 0;
    if (degenerate_triangle(mesh, tri))
      ++degenerate;
    else
      mesh.triangles.push_back(tri);
  }
  if (degenerate > 0) warnings.add(name, fmt::format("{} degenerate triangle(s) dropped", degenerate));
  if (mesh.triangles.empty()) throw InputError(name, "no triangles (every triangle is degenerate)");
  return mesh;
}

}  // namespace insitu
