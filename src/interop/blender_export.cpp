#include "interop/blender_export.h"

#include <filesystem>
#include <fmt/format.h>

#include "interop/blender_camera.h"
#include "core/text_file.h"
#include "light/preview.h"
#include "interop/blender_meshes.h"
#include "render/gltf_mesh.h"
#include "scene/catcher_albedo.h"

namespace insitu {
namespace fs = std::filesystem;
namespace {

std::string abs_path(const std::string& p) { return fs::absolute(p).lexically_normal().string(); }

std::string py_vec(const Vec3d& v) { return fmt::format("({:.9g}, {:.9g}, {:.9g})", v[0], v[1], v[2]); }

std::string py_quads(const std::vector<Quad>& quads) {
  std::string s = "[";
  for (const Quad& q : quads)
    s += fmt::format("({}, {}, {}, {}),\n    ", py_vec(to_blender(q[0])), py_vec(to_blender(q[1])),
                     py_vec(to_blender(q[2])), py_vec(to_blender(q[3])));
  return s + "]";
}

// The objects' bounds (or the camera's eye without objects) and the scene's size, for the
// infinite planes' squares.
void scene_extent(const LoadedScene& s, Vec3d& centre, double& size_m) {
  Bounds b;
  if (s.objects)
    for (const Mesh& m : s.objects->meshes())
      for (const Vec3f& p : m.positions) b.extend(p);
  const Vec3d eye = s.camera.eye_world();
  centre = (b.lo.array() <= b.hi.array()).all() ? Vec3d(0.5 * (b.lo + b.hi).cast<double>()) : eye;
  size_m = std::max(
      {1e-3, (eye - centre).norm(), (b.lo.array() <= b.hi.array()).all() ? double((b.hi - b.lo).norm()) : 0.0});
}

// An infinite plane as a square of half-side 1000 × the scene's size about the point nearest the
// objects, facing the camera (as the render's catcher does), counter-clockwise seen from its front.
Quad plane_square(const LoadedScene& s, const PlaneSpec& p) {
  Vec3d centre;
  double size_m = 0;
  scene_extent(s, centre, size_m);
  Vec3d n = p.normal.normalized();
  if (n.dot(s.camera.eye_world() - p.point) < 0) n = -n;
  const Vec3d c = centre - n * n.dot(centre - p.point);
  const Vec3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);  // t1 × t2 = n
  const double r = 1000.0 * size_m;
  return {c - r * t1 - r * t2, c + r * t1 - r * t2, c + r * t1 + r * t2, c - r * t1 + r * t2};
}

std::string albedo_comment(const CatcherAlbedo& a) {
  if (a.from_photo)
    return fmt::format("# albedo: the photo's mean over {} pixels (scene/catcher_albedo.h)\n", a.pixels);
  return "# albedo: the scene's (or 0.5 where the photo does not show the surface)\n";
}

std::string local_scene_lines(const LoadedScene& s, std::string& bytes) {
  const std::vector<CatcherAlbedo> albedo = catcher_albedos(s);
  std::string out;
  std::size_t mesh_index = 0;
  for (std::size_t k = 0; k < s.spec.local_scene.size(); ++k) {
    const PlaneSpec& p = s.spec.local_scene[k];
    const std::string name = fmt::format("local_scene[{}]", k);
    out += albedo_comment(albedo[k]);
    if (p.mesh) {
      out += blender_mesh(s.catcher_meshes->meshes()[mesh_index++],
                          name + " " + fs::path(p.mesh->mesh).filename().string(), albedo[k].albedo, bytes);
      continue;
    }
    out += fmt::format("catcher(quads_object(scene, {}, {}, surface_material({}, {})))\n", py_string(name + " (plane)"),
                       py_quads({plane_square(s, p)}), py_string(name + ": albedo"), py_rgb(albedo[k].albedo));
  }
  return out;
}

// A glTF object imports the user's file, or the decompressed copy written beside the script.
std::string gltf_lines(const ObjectSpec& o, std::size_t i, const std::string& name, const BlenderExportPaths& paths,
                       BlenderExport& e) {
  std::optional<std::string> copy = gltf_plain_copy(o.mesh);
  if (!copy) return blender_gltf_object(py_string(abs_path(o.mesh)), name, o.M_world_from_object);
  const std::string path = paths.gltf_copy(i);
  e.gltf_copies.emplace_back(path, std::move(*copy));
  const std::string py_path =
      fmt::format("data_file({}, {})", py_string(fs::path(path).filename().string()), py_string(abs_path(path)));
  return blender_gltf_object(py_path, name + " (decompressed)", o.M_world_from_object);
}

std::string objects_lines(const LoadedScene& s, const BlenderExportPaths& paths, BlenderExport& e) {
  std::string out;
  if (!s.objects) return out;
  for (std::size_t i = 0; i < s.objects->meshes().size(); ++i) {
    const ObjectSpec& o = s.spec.objects[i];
    const std::string name = fmt::format("objects[{}] {}", i, fs::path(o.mesh).filename().string());
    out += is_gltf_path(o.mesh) ? gltf_lines(o, i, name, paths, e)
                                : blender_mesh(s.objects->meshes()[i], name, std::nullopt, e.mesh_bytes);
  }
  return out;
}

std::string header(const LoadedScene& s, const BlenderExportPaths& paths) {
  const std::string py = fs::path(paths.script).filename().string();
  std::string h =
      fmt::format("# Written by insitu export-blender from {} (src/interop/blender_export.h).\n", s.spec.path);
  h += "#   blender --python " + py + "                         builds the scene in a new scene \"insitu\"\n";
  h += "#   blender -b --python " + py +
       " -- --render out.png [--samples N] [--seed S]   renders the composite over the photo\n";
  h += "# It reads " + fs::path(paths.meshes).filename().string() + " and " +
       fs::path(paths.world).filename().string() + " beside it.\n";
  return h;
}

int max_bounces(const LoadedScene& s) {
  const auto it = s.integrator.params.find("max_depth");
  return it != s.integrator.params.end() ? it->get<int>() : 5;  // the path integrator's default
}

// The world seen through the openings: the environment, with the directions the capture point
// saw as wall given the unseen outside where the photo determined it (light/room_light.h).
std::optional<CubeMap> outside_world(const LoadedScene& s) {
  if (!s.room || !s.room->unseen_outside) return std::nullopt;
  return RoomLight(CubeMap(1), s.room).seen_through_openings(s.environment);
}

}  // namespace

BlenderExportPaths blender_export_paths(const std::string& script_path) {
  fs::path p(script_path);
  const fs::path stem = p.extension() == ".py" ? p.replace_extension() : p;
  return {script_path, stem.string() + ".meshes.bin", stem.string() + ".world.exr", stem.string() + ".outside.exr",
          stem.string()};
}

std::string BlenderExportPaths::gltf_copy(std::size_t i) const { return fmt::format("{}.objects{}.glb", stem, i); }

BlenderExport make_blender_export(const LoadedScene& s, const BlenderExportPaths& paths) {
  BlenderExport e;
  e.world = cube_to_equirect(s.environment);
  if (const std::optional<CubeMap> outside = outside_world(s)) e.outside = cube_to_equirect(*outside);
  std::string& py = e.script;
  py = header(s, paths) + kBlenderExportPrelude + "\n";
  py += fmt::format("MESHES = data_file({}, {})\n", py_string(fs::path(paths.meshes).filename().string()),
                    py_string(abs_path(paths.meshes)));
  py += fmt::format("WORLD = data_file({}, {})\n", py_string(fs::path(paths.world).filename().string()),
                    py_string(abs_path(paths.world)));
  py += "scene = new_scene('insitu')\n";
  py += fmt::format("render_settings(scene, {}, {}, {})\n", s.spec.render.spp, max_bounces(s),
                    s.spec.render.seed % 2147483647);
  py += blender_camera_lines(s.camera, s.spec.photo);
  if (e.outside.width > 0)
    py += fmt::format("set_world(scene, data_file({}, {}))\n", py_string(fs::path(paths.outside).filename().string()),
                      py_string(abs_path(paths.outside)));
  else
    py += "set_world(scene, WORLD)\n";
  if (const auto& box = s.spec.environment.room_box)
    py += fmt::format("room_box(scene, {}, WORLD, {})\n", py_quads(room_wall_quads(*box, s.spec.local_scene)),
                      py_vec(to_blender(box->capture)));
  py += local_scene_lines(s, e.mesh_bytes);
  py += objects_lines(s, paths, e);
  py += fmt::format("composite_over_photo(scene, {}, {})\n", py_string(abs_path(s.spec.photo)),
                    s.photo.display_referred ? "False" : "True");
  py += "run_from_command_line(scene)\n";
  return e;
}

void write_blender_export(const BlenderExport& e, const BlenderExportPaths& paths) {
  for (const auto& [path, bytes] : e.gltf_copies) write_binary_file(path, bytes);
  write_image(paths.world, e.world);
  if (e.outside.width > 0) write_image(paths.outside, e.outside);
  write_binary_file(paths.meshes, e.mesh_bytes);
  write_text_file(paths.script, e.script);
}

}  // namespace insitu
