#include "interop/blender_meshes.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/json_reader.h"

namespace insitu {
namespace {

// Raw little-endian values (the file's layout; every platform insitu builds on is little-endian).
template <class T>
void append(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

void append_vec(std::string& bytes, const Vec3d& v) {
  for (int k = 0; k < 3; ++k) append(bytes, float(v[k]));
}

Vec3d geometric_normal(const Mesh& m, const Triangle& t) {
  const Vec3f& a = m.positions[t.v[0]];
  const Vec3d n = (m.positions[t.v[1]] - a).cross(m.positions[t.v[2]] - a).cast<double>();
  return n.norm() > 0 ? n.normalized() : Vec3d(0, 1, 0);
}

bool any_normals(const Mesh& m) {
  for (const Triangle& t : m.triangles)
    if (t.n[0] >= 0 || t.n[1] >= 0 || t.n[2] >= 0) return true;
  return false;
}

// Blender's roughness r for insitu's GGX α = √(2/(Ns + 2)) (render/bsdf.h): Blender squares it,
// α = r², so r = α^½.
double blender_roughness(float ns) { return std::sqrt(std::sqrt(2.0 / (std::max(0.0f, ns) + 2.0))); }

// A texture for blender_prelude.py's image_node: its file, with the Mapping node's Scale s and
// Location o where its placement (an MTL's -s and -o; render/obj_materials.cpp) is not the OBJ
// convention's, image_from_uv = [[s_u, 0, o_u], [0, −s_v, 1 − o_v]].
std::string py_texture(const Texture& t) {
  const std::string path =
      py_string(t.path.empty() ? "" : std::filesystem::absolute(t.path).lexically_normal().string());
  const Eigen::Matrix<float, 2, 3>& a = t.image_from_uv;
  if (t.path.empty() || a == Texture::obj_convention()) return path;
  return fmt::format("{{\"path\": {}, \"scale\": ({:.9g}, {:.9g}), \"offset\": ({:.9g}, {:.9g})}}", path, a(0, 0),
                     -a(1, 1), a(0, 2), 1 - a(1, 2));
}

// What either MTL model adds (blender_prelude.py's surface_extras): emission, a normal map, and
// the opacity of `d` and `map_d` (its alpha channel, or its grey where it has none).
std::string extras_entries(const Material& m) {
  return fmt::format(
      "\"emission\": {}, \"emission_texture\": {}, \"normal_texture\": {}, \"normal_strength\": {:.9g}, "
      "\"opacity\": {:.9g}, \"opacity_texture\": {}, \"opacity_channel\": {}",
      py_rgb(m.emission), py_texture(m.map_emission), py_texture(m.map_normal), m.normal_strength,
      m.cutout() ? m.alpha : 1.0f, py_texture(m.map_opacity), py_string(m.map_opacity.alpha ? "Alpha" : "Color"));
}

// An OBJ's material in Blender: the obj model's surface_material, or the principled model's
// principled_material (render/obj_materials.h), with the same values and maps.
std::string material_line(const Material& m, const std::string& object_name) {
  const std::string name = py_string(object_name + ": " + m.name);
  if (!m.principled)
    return fmt::format("surface_material({}, {}, {}, {}, {:.9g}, {{{}}})", name, py_rgb(m.kd), py_texture(m.map_kd),
                       py_rgb(m.ks), blender_roughness(m.ns), extras_entries(m));
  return fmt::format(
      "principled_material({}, {{\"base\": {}, \"base_texture\": {}, \"metallic\": {:.9g}, \"metallic_texture\": {}, "
      "\"roughness\": {:.9g}, \"roughness_texture\": {}, \"specular\": {:.9g}, \"clearcoat\": {:.9g}, "
      "\"clearcoat_roughness\": {:.9g}, \"transmission\": {:.9g}, \"ior\": {:.9g}, {}}})",
      name, py_rgb(m.kd), py_texture(m.map_kd), m.metallic, py_texture(m.map_metallic), m.roughness,
      py_texture(m.map_roughness), m.specular, m.clearcoat, m.clearcoat_roughness, m.transmission, m.ior,
      extras_entries(m));
}

}  // namespace

std::string py_string(const std::string& s) { return json_text(nlohmann::json(s)); }

std::string py_rgb(const Rgb& c) { return fmt::format("({:.9g}, {:.9g}, {:.9g})", c[0], c[1], c[2]); }

std::string blender_mesh(const Mesh& m, const std::string& name, const std::optional<Rgb>& catcher_albedo,
                         std::string& bytes) {
  const std::size_t offset = bytes.size();
  const bool normals = any_normals(m), uvs = !m.uvs.empty();
  for (const Vec3f& p : m.positions) append_vec(bytes, to_blender(p.cast<double>()));
  for (const Triangle& t : m.triangles)
    for (auto v : t.v) append(bytes, std::uint32_t(v));
  for (const Triangle& t : m.triangles) append(bytes, std::int32_t(catcher_albedo ? 0 : t.material));
  if (normals)
    for (const Triangle& t : m.triangles)
      for (int k = 0; k < 3; ++k)
        append_vec(bytes, to_blender(t.n[k] >= 0 ? m.normals[std::size_t(t.n[k])].cast<double>().normalized()
                                                 : geometric_normal(m, t)));
  if (uvs)
    for (const Triangle& t : m.triangles)
      for (int k = 0; k < 3; ++k) {
        const Vec2f uv = t.t[k] >= 0 ? m.uvs[std::size_t(t.t[k])] : Vec2f::Zero();
        append(bytes, uv.x()), append(bytes, uv.y());
      }
  std::string materials;
  if (catcher_albedo) {
    materials = fmt::format("surface_material({}, {})", py_string(name + ": albedo"), py_rgb(*catcher_albedo));
  } else {
    for (const Material& mat : m.materials) materials += (materials.empty() ? "" : ", ") + material_line(mat, name);
  }
  std::string s = fmt::format("obj = load_mesh(scene, {}, MESHES, {}, {}, {}, {}, {}, [{}])\n", py_string(name), offset,
                              m.positions.size(), m.triangles.size(), normals ? "True" : "False",
                              uvs ? "True" : "False", materials);
  if (catcher_albedo) s += "catcher(obj)\n";
  return s;
}

std::string blender_gltf_object(const std::string& py_path, const std::string& name, const Mat4d& M_world_from_object) {
  Mat4d B = Mat4d::Identity();
  B.topLeftCorner<3, 3>() = blender_from_insitu();
  const Mat4d M = B * M_world_from_object * B.inverse();
  std::string rows;
  for (int r = 0; r < 4; ++r)
    rows +=
        fmt::format("({:.17g}, {:.17g}, {:.17g}, {:.17g}){}", M(r, 0), M(r, 1), M(r, 2), M(r, 3), r < 3 ? ", " : "");
  return fmt::format("gltf_object(scene, {}, {}, ({}))\n", py_string(name), py_path, rows);
}

}  // namespace insitu
