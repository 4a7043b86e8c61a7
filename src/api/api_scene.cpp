// insitu.h: scenes, their settings, objects and cameras.
#include <filesystem>
#include <fmt/format.h>

#include "api/api_internal.h"
#include "core/json_reader.h"
#include "render/mesh_arrays.h"
#include "scene/scene_file.h"

namespace fs = std::filesystem;
using namespace insitu;
using insitu::api::guarded;
using insitu::api::not_null;
using insitu::api::require;

namespace insitu::api {

namespace {
thread_local std::string last_error;
}

void set_last_error(const std::string& message) { last_error = message; }

void reparse(insitu_scene& s, json doc) {
  SceneSpec spec = parse_scene_json(doc, s.name, s.base_dir);
  if (s.points) {
    spec.camera = CameraSpec{};
    spec.camera.kind = CameraSpec::Kind::Points;
    spec.camera.where = s.name + ":$.camera";
    spec.camera.point_list = *s.points;
    spec.camera.model = s.points_model;
  }
  Warnings ignored;                                                        // (given again when the scene loads)
  resolve_integrator(spec.render.integrator, spec.render.block, ignored);  // its parameters, now
  s.spec = std::move(spec);
  s.doc = std::move(doc);
  s.loaded.reset();
}

const LoadedScene& loaded(insitu_scene& s) {
  if (s.loaded) return *s.loaded;
  auto scene = std::make_shared<LoadedScene>(load_scene(s.spec, s.memory_meshes));
  if (s.camera_size && (s.camera_size->first != scene->camera.width || s.camera_size->second != scene->camera.height))
    throw InputError(s.name + ":$.camera",
                     fmt::format("the camera is for {}x{} images, the photo is {}x{}", s.camera_size->first,
                                 s.camera_size->second, scene->camera.width, scene->camera.height));
  s.warnings_text.clear();
  for (const auto& w : s.mesh_warnings.items) s.warnings_text += w + "\n";
  for (const auto& w : scene->warnings.items) s.warnings_text += w + "\n";
  s.calibration_text = scene->calibration ? calibration_report(*scene->calibration) : "";
  s.loaded = std::move(scene);
  return *s.loaded;
}

}  // namespace insitu::api

namespace {

insitu_status make_scene(json doc, std::string name, std::string base_dir, insitu_scene** out) {
  return guarded([&] {
    require(out, "the scene pointer");
    *out = nullptr;
    auto scene = std::make_unique<insitu_scene>();
    scene->name = std::move(name);
    scene->base_dir = std::move(base_dir);
    insitu::api::reparse(*scene, std::move(doc));
    *out = scene.release();
  });
}

Mat4d matrix_or_identity(const double* m) {
  Mat4d M = Mat4d::Identity();
  if (m)
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) M(r, c) = m[4 * r + c];
  return M;
}

json matrix_json(const Mat4d& M) {
  json rows = json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({M(r, 0), M(r, 1), M(r, 2), M(r, 3)});
  return rows;
}

// "render.spp" -> the object that holds "spp", created on the way; the last key's name.
json& parent_of(json& doc, const std::string& key, std::string& last) {
  json* node = &doc;
  std::size_t start = 0;
  for (std::size_t dot; (dot = key.find('.', start)) != std::string::npos; start = dot + 1) {
    const std::string part = key.substr(start, dot - start);
    if (part.empty()) throw InputError(key, "an empty key in the dotted path");
    json& child = (*node)[part];
    if (child.is_null()) child = json::object();
    if (!child.is_object()) throw InputError(key, "'" + part + "' is not an object");
    node = &child;
  }
  last = key.substr(start);
  if (last.empty()) throw InputError(key, "an empty key in the dotted path");
  return *node;
}

}  // namespace

extern "C" {

int insitu_api_version(void) { return INSITU_API_VERSION; }
const char* insitu_version(void) { return INSITU_VERSION; }
const char* insitu_last_error(void) { return insitu::api::last_error.c_str(); }

insitu_status insitu_scene_from_file(const char* path, insitu_scene** scene) {
  json doc;
  std::string p;
  const insitu_status st = guarded([&] {
    p = not_null(path, "the scene path");
    doc = read_json_file(p);
  });
  if (st != INSITU_OK) return st;
  return make_scene(std::move(doc), p, fs::path(p).parent_path().string(), scene);
}

insitu_status insitu_scene_from_json(const char* text, const char* base_dir, const char* name, insitu_scene** scene) {
  json doc;
  const std::string n = name ? name : "<json>";
  const insitu_status st = guarded([&] { doc = parse_json_text(not_null(text, "the JSON text"), n); });
  if (st != INSITU_OK) return st;
  return make_scene(std::move(doc), n, base_dir ? base_dir : "", scene);
}

void insitu_scene_free(insitu_scene* scene) { delete scene; }

insitu_status insitu_scene_set(insitu_scene* scene, const char* key, const char* json_value) {
  return guarded([&] {
    insitu_scene& s = require(scene, "the scene");
    const std::string k = not_null(key, "the key");
    json doc = s.doc;
    std::string last;
    json& parent = parent_of(doc, k, last);
    parent[last] = parse_json_text(not_null(json_value, "the value"), k);
    insitu::api::reparse(s, std::move(doc));
  });
}

insitu_status insitu_scene_add_obj(insitu_scene* scene, const char* obj_path, const double world_from_object[16]) {
  return guarded([&] {
    insitu_scene& s = require(scene, "the scene");
    json doc = s.doc;
    // A path the caller gives is the caller's, not relative to the scene file.
    doc["objects"].push_back({{"mesh", fs::absolute(not_null(obj_path, "the OBJ path")).string()},
                              {"matrix", matrix_json(matrix_or_identity(world_from_object))}});
    insitu::api::reparse(s, std::move(doc));
  });
}

void insitu_mesh_init(insitu_mesh* mesh) {
  if (!mesh) return;
  *mesh = insitu_mesh{};
  for (float& k : mesh->kd) k = 0.8f;
}

insitu_status insitu_scene_add_mesh(insitu_scene* scene, const insitu_mesh* mesh, const double world_from_object[16],
                                    const char* name) {
  return guarded([&] {
    insitu_scene& s = require(scene, "the scene");
    const insitu_mesh& m = require(mesh, "the mesh");
    const std::string n = name ? name : fmt::format("mesh {}", s.memory_meshes.size());
    MeshArrays a{m.positions,
                 m.vertex_count,
                 m.normals,
                 m.uvs,
                 m.indices,
                 m.triangle_count,
                 Rgb(m.kd[0], m.kd[1], m.kd[2]),
                 Rgb(m.ks[0], m.ks[1], m.ks[2]),
                 m.ns,
                 m.map_kd,
                 m.map_kd_width,
                 m.map_kd_height};
    Warnings warnings;
    Mesh placed = mesh_from_arrays(a, n, warnings);
    const Mat4d M = matrix_or_identity(world_from_object);
    if ((M.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() != 0)
      throw InputError(n + ": world_from_object", "the last row must be [0, 0, 0, 1] (affine transforms only)");
    try {
      transform_mesh(placed, M);
    } catch (const InputError& e) {
      throw e.with_context(n);
    }
    s.memory_meshes.push_back(std::move(placed));
    for (const auto& w : warnings.items) s.mesh_warnings.items.push_back(w);
    s.loaded.reset();
  });
}

}  // extern "C"
