// render_fingerprint (scene/pipeline.h): what a checkpoint must match to be resumed.
#include <cstring>
#include <string>

#include "core/fnv1a.h"
#include "scene/pipeline.h"

namespace insitu {
namespace {

void add_camera(Fnv1a& h, const Camera& c) {
  h.value(c.width), h.value(c.height), h.value(c.fx), h.value(c.fy), h.value(c.cx), h.value(c.cy);
  h.bytes(c.R_cam_from_world.data(), 9 * sizeof(double)), h.bytes(c.t_cam_from_world.data(), 3 * sizeof(double));
}

void add_texels(Fnv1a& h, const Texels& t) { h.array(t.bytes.data), h.array(t.floats.data); }

void add_texture(Fnv1a& h, const Texture& t) {
  h.value(bool(t));
  if (!t) return;
  add_texels(h, *t.image), h.value(t.texcoord), h.bytes(t.image_from_uv.data(), 6 * sizeof(float));
  h.value(bool(t.alpha));
  if (t.alpha) add_texels(h, *t.alpha);
}

void add_meshes(Fnv1a& h, const EmbreeScene* scene) {
  if (!scene) return;
  for (const Mesh& m : scene->meshes()) {
    h.array(m.positions), h.array(m.normals), h.array(m.uvs), h.array(m.uvs1), h.array(m.triangles);
    for (const Material& mat : m.materials) {
      h.bytes(mat.kd.data(), sizeof(Rgb)), h.bytes(mat.ks.data(), sizeof(Rgb)), h.value(mat.ns);
      add_texture(h, mat.map_kd);
      h.value(mat.principled), h.value(mat.metallic), h.value(mat.roughness), h.value(mat.specular);
      add_texture(h, mat.map_metallic_roughness), add_texture(h, mat.map_roughness), add_texture(h, mat.map_metallic);
      h.value(mat.clearcoat), h.value(mat.clearcoat_roughness);
      add_texture(h, mat.map_clearcoat), add_texture(h, mat.map_clearcoat_roughness);
      h.bytes(mat.emission.data(), sizeof(Rgb)), add_texture(h, mat.map_emission);
      h.bytes(mat.sheen.data(), sizeof(Rgb)), h.value(mat.sheen_roughness);
      add_texture(h, mat.map_sheen), add_texture(h, mat.map_sheen_roughness);
      h.value(mat.alpha_mode), h.value(mat.alpha), h.value(mat.alpha_cutoff);
      add_texture(h, mat.map_opacity);
      h.value(mat.transmission), h.value(mat.ior), h.bytes(mat.absorption.data(), sizeof(Rgb));
      add_texture(h, mat.map_transmission), add_texture(h, mat.map_normal), h.value(mat.normal_strength);
      add_texture(h, mat.map_clearcoat_normal), h.value(mat.clearcoat_normal_strength);
      h.value(mat.has_specular_colour), h.bytes(mat.specular_colour.data(), sizeof(Rgb));
      h.value(mat.specular_factor), add_texture(h, mat.map_specular), add_texture(h, mat.map_specular_colour);
    }
  }
}

void add_local_scene(Fnv1a& h, const LoadedScene& s) {
  for (const PlaneSpec& p : s.spec.local_scene) {
    h.bytes(p.point.data(), 3 * sizeof(double)), h.bytes(p.normal.data(), 3 * sizeof(double));
    h.value(p.albedo_from_photo), h.bytes(p.albedo.data(), sizeof(Rgb)), h.value(bool(p.mesh));
  }
  if (s.room) {
    h.bytes(s.room->min.data(), 3 * sizeof(float)), h.bytes(s.room->max.data(), 3 * sizeof(float));
    h.bytes(s.room->capture.data(), 3 * sizeof(float));
    for (const RoomOpening& o : s.room->openings)
      h.value(o.axis), h.bytes(o.min.data(), 3 * sizeof(float)), h.bytes(o.max.data(), 3 * sizeof(float));
  }
}

}  // namespace

std::uint64_t render_fingerprint(const LoadedScene& s) {
  Fnv1a h;
  h.text("insitu render state 3");  // 2: scrambled Sobol points (core/sampler.h); 3: their seeds per pair
  add_camera(h, s.camera);
  h.value(s.spec.render.spp), h.value(s.spec.render.seed), h.value(s.spec.render.noise_target);
  h.text(s.spec.render.integrator), h.text(s.integrator.params.dump());
  h.array(s.photo_linear.data);
  for (int f = 0; f < 6; ++f) h.array(s.environment.face_image(f).data);
  add_local_scene(h, s);
  add_meshes(h, s.objects.get());
  add_meshes(h, s.catcher_meshes.get());
  return h.digest();
}

}  // namespace insitu
