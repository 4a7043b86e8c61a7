#include "core/output_paths.h"
#include "render/mesh.h"
#include "render/obj_materials.h"
#include "render/obj_statements.h"
#include "render/tangents.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <unordered_set>

namespace insitu {

float Material::opacity(const UvSets& uv) const {
  if (alpha_mode == AlphaMode::kOpaque) return 1.0f;
  float a = alpha * map_kd.sample_alpha(uv);
  if (map_opacity) a *= map_opacity.alpha ? map_opacity.sample_alpha(uv) : luminance(map_opacity.sample(uv));
  if (alpha_mode == AlphaMode::kMask) return a >= alpha_cutoff ? 1.0f : 0.0f;
  return std::clamp(a, 0.0f, 1.0f);
}

// Blender 3.4's importer (io_scene_gltf2/blender/imp/gltf2_blender_KHR_materials_specular.py):
//   tint = clamp(lum((ĉ_s − 1) / (ĉ_b − 1)), 0, 1),  ĉ = c / lum(c),  lum(c) = 0.3 R + 0.6 G + 0.1 B,
// per channel, with c_s the specular colour and c_b the base colour (ĉ = c where lum(c) = 0); 1
// where the base is grey (ĉ_b = 1). A channel's 0/0 counts 0 and x/0 ±∞, as numpy's nan_to_num
// in the importer's per-texel path. Blender bakes that path into a texture; this is the same
// formula at the shading point.
float Material::specular_tint(const Rgb& base, const Rgb& colour) const {
  if (!has_specular_colour) return 0.0f;
  auto hue = [](const Rgb& c) {
    const float lum = cycles_tint_luminance(c);
    return lum > 0 ? Rgb(c / lum) : c;
  };
  const Rgb s = hue(colour) - 1.0f, b = hue(base) - 1.0f;
  if ((b == 0.0f).all()) return 1.0f;
  const float kBig = 1e30f;  // ±∞ that stays finite through the weighted sum
  Rgb ratio;
  for (int k = 0; k < 3; ++k) ratio[k] = b[k] != 0 ? s[k] / b[k] : (s[k] == 0 ? 0.0f : std::copysign(kBig, s[k]));
  return std::clamp(cycles_tint_luminance(ratio), 0.0f, 1.0f);
}

// KHR_materials_specular as Blender 3.4's importer converts it, per point as its texture path
// does per texel:
//   Specular = f · a · (lum(c) − t)/(1 − t) · F0(ior)/0.08,  F0 = ((ior − 1)/(ior + 1))²,
// c = specularColorFactor × specularColorTexture, t the transmission there (left out where t = 1,
// where Blender divides by 0), at least 0. f · a, specularFactor × specularTexture's alpha, is
// glTF's and not Blender's: its importer drops both. Blender also reads the colour texture's
// stored sRGB values in its bake; glTF's colour is linear, and so it is here (docs/materials.md).
float Material::specular_at(const UvSets& uv, float t) const {
  if (!has_specular_colour) return specular;
  const float lum = cycles_tint_luminance(specular_colour_at(uv));
  const float r = (ior - 1) / (ior + 1), f0 = r * r;
  const float strength = specular_factor * map_specular.sample_alpha(uv);  // 1 without the texture
  return std::max(0.0f, strength * (t < 1 ? (lum - t) / (1 - t) : lum) * f0 / 0.08f);
}

namespace fs = std::filesystem;

namespace {

using namespace obj_text;

// ---- The validating pass -------------------------------------------------------------------

struct ObjScan {
  std::vector<int> face_lines;       // line of every `f` statement, in file order
  std::vector<std::string> mtllibs;  // the MTL files it names
};

// One index of a face corner: 1-based, negative counts back from the latest; must name an
// element defined before this line.
void check_index(const std::string& path, int line, const std::string& text, long count, const char* kind) {
  char* end = nullptr;
  const long idx = std::strtol(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0')
    fail(path, line, fmt::format("face {} index '{}' is not an integer", kind, text));
  if (idx == 0) fail(path, line, fmt::format("face {} index 0 (OBJ indices start at 1)", kind));
  const long resolved = idx > 0 ? idx : count + idx + 1;
  if (resolved < 1 || resolved > count)
    fail(path, line, fmt::format("face {} index {} out of range ({} defined so far)", kind, idx, count));
}

ObjScan scan_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "file not found or unreadable");
  ObjScan scan;
  long nv = 0, nvt = 0, nvn = 0;
  for_each_statement(in, [&](int lineno, const std::vector<std::string>& tok) {
    const std::string& kw = tok[0];
    if (kw == "v") {
      check_numbers(path, lineno, tok, 3, 6, "vertex");
      ++nv;
    } else if (kw == "vn") {
      check_numbers(path, lineno, tok, 3, 3, "normal");
      ++nvn;
    } else if (kw == "vt") {
      check_numbers(path, lineno, tok, 1, 3, "texture coordinate");
      ++nvt;
    } else if (kw == "mtllib") {
      for (std::size_t k = 1; k < tok.size(); ++k) scan.mtllibs.push_back(tok[k]);
    } else if (kw == "f") {
      if (tok.size() < 4) fail(path, lineno, fmt::format("face has {} vertices, needs at least 3", tok.size() - 1));
      for (std::size_t k = 1; k < tok.size(); ++k) {
        const std::string& c = tok[k];
        const auto s1 = c.find('/');
        check_index(path, lineno, c.substr(0, s1), nv, "vertex");
        if (s1 == std::string::npos) continue;
        const auto s2 = c.find('/', s1 + 1);
        const std::string vt = c.substr(s1 + 1, s2 == std::string::npos ? std::string::npos : s2 - s1 - 1);
        if (!vt.empty()) check_index(path, lineno, vt, nvt, "texture");
        if (s2 != std::string::npos) check_index(path, lineno, c.substr(s2 + 1), nvn, "normal");
      }
      scan.face_lines.push_back(lineno);
    }
  });
  return scan;
}

}  // namespace

// Degenerate: |e1 × e2| <= 1e-12 (|e1|² + |e2|²), in double, scale-free.
bool degenerate_triangle(const Mesh& mesh, const Triangle& tri) {
  const Vec3d p0 = mesh.positions[tri.v[0]].cast<double>();
  const Vec3d e1 = mesh.positions[tri.v[1]].cast<double>() - p0;
  const Vec3d e2 = mesh.positions[tri.v[2]].cast<double>() - p0;
  return e1.cross(e2).norm() <= 1e-12 * (e1.squaredNorm() + e2.squaredNorm()) ||
         (e1.squaredNorm() + e2.squaredNorm()) == 0.0;
}

namespace {

// An index tinyobjloader gives: 0-based, −1 for "none" where that is allowed.
bool index_in_range(int index, std::size_t count, bool may_be_absent) {
  return (may_be_absent && index == -1) || (index >= 0 && std::size_t(index) < count);
}

// A triangle's three corners as positions, in a fixed order: two triangles with the same key are
// one surface whatever their vertex indices, winding or first corner.
using CornerKey = std::array<float, 9>;
CornerKey corner_key(const Mesh& mesh, const Triangle& tri) {
  std::array<std::array<float, 3>, 3> c;
  for (int k = 0; k < 3; ++k) {
    const Vec3f& p = mesh.positions[tri.v[std::size_t(k)]];
    c[std::size_t(k)] = {p.x(), p.y(), p.z()};
  }
  std::sort(c.begin(), c.end());
  CornerKey key;
  for (int k = 0; k < 9; ++k) key[std::size_t(k)] = c[std::size_t(k / 3)][std::size_t(k % 3)];
  return key;
}

struct CornerKeyHash {
  std::size_t operator()(const CornerKey& k) const {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the nine floats' bytes
    for (float f : k) {
      std::uint32_t bits;
      std::memcpy(&bits, &f, sizeof bits);
      for (int b = 0; b < 4; ++b) h = (h ^ ((bits >> (8 * b)) & 0xffu)) * 1099511628211ull;
    }
    return std::size_t(h);
  }
};

// Polygons fanned into triangles, each keeping its OBJ line; degenerate ones, |e1 × e2| ≤
// 1e-12 (|e1|² + |e2|²) in double (scale-free), are dropped and counted in one warning. So are
// copies of a triangle already read (the same three corners): a copy adds no surface, only a hit
// that every ray through it must also test (10⁶ copies of one triangle rendered 1000× slower).
void add_triangles(const std::vector<tinyobj::shape_t>& shapes, const ObjScan& scan, int default_material,
                   const std::string& path, Mesh& mesh, Warnings& warnings) {
  std::size_t face_no = 0, degenerate = 0, copies = 0;
  int first_degenerate_line = 0, first_copy_line = 0;
  std::unordered_set<CornerKey, CornerKeyHash> seen;
  for (const auto& shape : shapes) {
    std::size_t offset = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++face_no) {
      const std::size_t nfv = shape.mesh.num_face_vertices[f];
      const int line = face_no < scan.face_lines.size() ? scan.face_lines[face_no] : 0;
      int mat = shape.mesh.material_ids.empty() ? -1 : shape.mesh.material_ids[f];
      if (mat < 0 || mat >= default_material) mat = default_material;
      for (std::size_t k = 1; k + 1 < nfv; ++k) {
        const tinyobj::index_t corner[3] = {shape.mesh.indices[offset], shape.mesh.indices[offset + k],
                                            shape.mesh.indices[offset + k + 1]};
        Triangle tri;
        for (int c = 0; c < 3; ++c) {
          // The scan checked every index as the OBJ reads; tinyobjloader may still read a line
          // differently (a keyword followed by '\r' is a vertex to one and not to the other).
          if (!index_in_range(corner[c].vertex_index, mesh.positions.size(), false) ||
              !index_in_range(corner[c].normal_index, mesh.normals.size(), true) ||
              !index_in_range(corner[c].texcoord_index, mesh.uvs.size(), true))
            throw InputError(fmt::format("{}:{}", path, line),
                             "face index out of range of the vertices tinyobjloader read");
          tri.v[c] = std::uint32_t(corner[c].vertex_index);
          tri.n[c] = corner[c].normal_index;
          tri.t[c] = corner[c].texcoord_index;
        }
        tri.material = mat;
        if (degenerate_triangle(mesh, tri)) {
          if (degenerate++ == 0) first_degenerate_line = line;
          continue;
        }
        if (!seen.insert(corner_key(mesh, tri)).second) {
          if (copies++ == 0) first_copy_line = line;
          continue;
        }
        mesh.triangles.push_back(tri);
      }
      offset += nfv;
    }
  }
  if (degenerate > 0)
    warnings.add(
        path, fmt::format("{} degenerate triangle(s) dropped (first at line {})", degenerate, first_degenerate_line));
  if (copies > 0)
    warnings.add(path,
                 fmt::format("{} triangle(s) dropped that repeat another's three corners exactly (first at line {}): a "
                             "copy adds no surface and slows every ray through it",
                             copies, first_copy_line));
}

}  // namespace

std::vector<std::string> obj_dependencies(const std::string& obj_path) {
  std::vector<std::string> files;
  std::ifstream obj(obj_path);
  if (!obj) return files;
  const fs::path base_dir = fs::path(obj_path).parent_path();
  for_each_statement(obj, [&](int, const std::vector<std::string>& tok) {
    if (tok[0] == "mtllib")
      for (std::size_t k = 1; k < tok.size(); ++k) files.push_back(beside_obj(base_dir, tok[k]));
  });
  const std::size_t mtl_count = files.size();
  for (std::size_t i = 0; i < mtl_count; ++i) {
    std::ifstream mtl(files[i]);
    std::map<std::string, int> names;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    if (!mtl) continue;
    tinyobj::LoadMtl(&names, &materials, &mtl, &warning, &error);
    for (const tinyobj::material_t& m : materials)
      for (std::string& f : material_files(m, base_dir)) files.push_back(std::move(f));
  }
  return files;
}

Mesh load_obj(const std::string& path, Warnings& warnings) {
  const std::string ext = lower_extension(path);
  if (ext != ".obj")
    throw InputError(path, fmt::format("only OBJ and glTF meshes are supported ('{}'): convert it to .glb, "
                                       "e.g. in Blender",
                                       ext.empty() ? "no extension" : ext));
  const ObjScan scan = scan_obj(path);
  const fs::path base_dir = fs::path(path).parent_path();
  MtlStatements statements;
  for (const auto& m : scan.mtllibs) scan_mtl(beside_obj(base_dir, m), statements);

  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // we fan polygons ourselves so each triangle keeps its line
  config.vertex_color = false;
  config.mtl_search_path = base_dir.string();
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    std::string err = reader.Error();
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw InputError(path, err.empty() ? "cannot parse OBJ" : err);
  }
  std::istringstream warn_lines(reader.Warning());
  for (std::string w; std::getline(warn_lines, w);)
    if (!w.empty()) warnings.add(path, w);

  const auto& attrib = reader.GetAttrib();
  Mesh mesh;
  mesh.source = path;
  mesh.files.push_back(path);
  for (const auto& m : scan.mtllibs) mesh.files.push_back(beside_obj(base_dir, m));
  for (std::size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
    mesh.positions.emplace_back(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]);
  for (std::size_t i = 0; i + 2 < attrib.normals.size(); i += 3) {
    Vec3f n(attrib.normals[i], attrib.normals[i + 1], attrib.normals[i + 2]);
    mesh.normals.push_back(n.norm() > 0 ? n.normalized() : n);
  }
  for (std::size_t i = 0; i + 1 < attrib.texcoords.size(); i += 2)
    mesh.uvs.emplace_back(attrib.texcoords[i], attrib.texcoords[i + 1]);
  for (const auto& m : reader.GetMaterials()) {
    mesh.materials.push_back(convert_material(m, statements[m.name], base_dir, path, warnings));
    for (std::string& f : material_files(m, base_dir)) mesh.files.push_back(std::move(f));
  }
  const int default_material = int(mesh.materials.size());
  mesh.materials.push_back(Material{});

  add_triangles(reader.GetShapes(), scan, default_material, path, mesh, warnings);
  if (mesh.triangles.empty()) throw InputError(path, "no triangles (the mesh has no usable faces)");
  if (std::any_of(mesh.materials.begin(), mesh.materials.end(),
                  [](const Material& m) { return bool(m.tangent_map()); }))
    mesh.tangents = mikktspace_tangents(mesh, 0);
  return mesh;
}

void transform_mesh(Mesh& mesh, const Mat4d& M) {
  const Eigen::Matrix3d A = M.topLeftCorner<3, 3>();
  const Vec3d t = M.topRightCorner<3, 1>();
  const Eigen::Matrix3d N = A.inverse().transpose();
  // Rays and positions are float: a transform (scale 1e300, translate 1e300) that takes a vertex
  // beyond float range, or one whose inverse transpose overflows (scale 1e-300), is refused.
  if (!M.allFinite() || !N.allFinite())
    throw InputError(
        "", "the transform is not finite, or not invertible in double precision (scale too small or too large)");
  for (Vec3f& p : mesh.positions) {
    const Vec3d q = A * p.cast<double>() + t;
    if (!(q.cwiseAbs().maxCoeff() < 1e30))
      throw InputError(
          "", fmt::format("the transform takes vertex ({}, {}, {}) to ({:.3g}, {:.3g}, {:.3g}): beyond the range "
                          "insitu renders (1e30 m)",
                          p.x(), p.y(), p.z(), q.x(), q.y(), q.z()));
    p = q.cast<float>();
  }
  for (Vec3f& n : mesh.normals) {
    const Vec3d m = N * n.cast<double>();
    n = (m.norm() > 0 ? m.normalized() : m).cast<float>();
  }
  // A mirroring transform turns the frame (n, t, n × t) left-handed: the bitangent's sign follows.
  const float handedness = A.determinant() < 0 ? -1.0f : 1.0f;
  for (Vec4f& tangent : mesh.tangents) {
    const Vec3d m = A * tangent.head<3>().cast<double>();
    tangent << (m.norm() > 0 ? m.normalized() : m).cast<float>(), tangent.w() * handedness;
  }
}

Bounds mesh_bounds(const Mesh& mesh) {
  Bounds b;
  for (const Triangle& t : mesh.triangles)
    for (auto v : t.v) b.extend(mesh.positions[v]);
  return b;
}

}  // namespace insitu
