// The Embree 3 scene of the objects: one triangle geometry per mesh, geometry ID = mesh index.
// Cut-out materials (Material::opacity) let rays through where they are absent, and each query
// treats a sheer one (0 < opacity < 1) its own way (render/cutouts.h): intersect() meets it with
// probability a, intersect_sheer() always, transmittance() is attenuated by 1 − a.
#pragma once
#include <memory>
#include <vector>

#include "core/camera.h"
#include "render/mesh.h"

struct RTCSceneTy;  // Embree's scene handle (RTCScene), for a bare loop over the same scene

namespace insitu {

class RayLog;            // render/ray_log.h
enum class CutoutQuery;  // render/cutouts.h

struct Hit {
  float t = 0;
  int mesh = -1, triangle = -1;  // -1: no hit
  float b1 = 0, b2 = 0;          // barycentrics of vertices 1 and 2
  bool valid() const { return mesh >= 0; }
};

// Shading data at a hit: positions and normals in world space, normals unit length and on the
// side the ray came from (two-sided surfaces, as the legacy renderer drew them).
struct SurfacePoint {
  Vec3f p_world;
  Vec3f ng_world;        // geometric normal
  Vec3f ns_world;        // shading normal: interpolated (the geometric one where the mesh has none), then mapped
  Vec3f n_smooth_world;  // the interpolated normal before the normal map (Cycles's sd->N)
  Vec3f n_coat_world;    // the clear coat's: the smooth one, or its own map's (Material::map_clearcoat_normal)
  UvSets uv = {Vec2f::Zero(), Vec2f::Zero()};
  const Material* material = nullptr;
  bool backfacing = false;  // the ray met the triangle's back (its winding's normal faced away from it)
};

// The UV sets of a triangle at barycentrics (b1, b2) of its vertices 1 and 2; zero without UVs.
UvSets uv_at(const Mesh& mesh, const Triangle& tri, float b1, float b2);

class EmbreeScene {
 public:
  explicit EmbreeScene(std::vector<Mesh> meshes);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  Hit intersect(const Ray& ray, float t_near = 0.0f, float t_far = std::numeric_limits<float>::infinity()) const;
  // The nearest surface that is there at all: a sheer one whatever its opacity (> 0), which the
  // caller weighs by it (Material::opacity at the hit).
  Hit intersect_sheer(const Ray& ray, float t_near = 0.0f, float t_far = std::numeric_limits<float>::infinity()) const;
  // The fraction of light that passes along the ray in (t_near, t_far): 0 where an opaque surface
  // lies on it, Π (1 − a_k) over the cut-out surfaces of opacity 0 < a_k < 1 it crosses, 1
  // where it crosses none (exactly 1: a shadow ray that meets nothing changes nothing).
  float transmittance(const Ray& ray, float t_near, float t_far) const;
  // Any hit that stops light in (t_near, t_far): transmittance() == 0.
  bool occluded(const Ray& ray, float t_near, float t_far) const { return transmittance(ray, t_near, t_far) == 0.0f; }
  SurfacePoint surface(const Ray& ray, const Hit& hit) const;
  const std::vector<Mesh>& meshes() const { return meshes_; }
  bool empty() const { return meshes_.empty(); }
  // Every ray traced from now on is appended to `log` (null: none, the default). Not to be changed
  // while a render runs.
  void set_ray_log(RayLog* log) { log_ = log; }
  RTCSceneTy* rtc_scene() const;

  struct Impl;  // Embree's device and scene (public for the error callback; defined in the .cpp)

 private:
  Hit nearest(const Ray& ray, float t_near, float t_far, CutoutQuery query) const;
  std::unique_ptr<Impl> impl_;
  std::vector<Mesh> meshes_;
  RayLog* log_ = nullptr;
};

}  // namespace insitu
