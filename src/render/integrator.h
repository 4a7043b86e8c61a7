// The integrator interface: what an integrator is given (RenderInputs) and what it returns for one
// camera ray (CameraSample). The integrators themselves live in src/integrators/, one per file, and
// src/integrators/registry.h maps their names to factories, parameters and capabilities.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "light/cubemap.h"
#include "render/embree_scene.h"
#include "light/room_cache.h"
#include "light/room_light.h"
#include "light/irradiance.h"
#include "core/sampler.h"

namespace insitu {

// What an integrator may use: the objects, and the room's light as a radiance cube.
// A plane of the local scene (the real floor): catches the objects' shadows and bounce light.
struct CatcherPlane {
  Vec3f point, normal;  // unit normal, on the side the camera sees
  bool albedo_from_photo = true;
  Rgb albedo = Rgb::Zero();
  Rgb irradiance = Rgb::Zero();  // E(normal) of the environment without objects (exact)
};

struct CatcherMesh {
  bool albedo_from_photo = true;
  Rgb albedo = Rgb::Zero();
};

struct RenderInputs {
  const EmbreeScene* objects = nullptr;
  const CubeMap* environment = nullptr;
  std::vector<CatcherPlane> planes;                     // the local scene: planes
  const EmbreeScene* catcher_meshes = nullptr;          // and meshes
  std::vector<CatcherMesh> catcher_mesh_info;           // by mesh index
  const IrradianceField* catcher_irradiance = nullptr;  // E(n) without objects, for the meshes
  const Image* photo_linear = nullptr;                  // the real room as the camera saw it
  // The room as an emitting box with openings (path; room_light.h): its walls, where the shots
  // were taken, and its windows.
  std::optional<RoomBox> room;
  const Camera* camera = nullptr;
  // The room's prepared light and grids, shared by every render of this room (room_cache.h);
  // null: the integrator prepares its own.
  std::shared_ptr<RoomCache> room_cache;
  // Looked at during the preparation (core/stop.h): once set, creating the integrator throws
  // Stopped. Null: the preparation runs to its end.
  const std::atomic<bool>* stop = nullptr;
};

// One camera sample: the objects' radiance where they cover the sample, and the coverage (0/1
// for a pinhole sample; averaged over samples it is the pixel's alpha).
struct CameraSample {
  Rgb radiance = Rgb::Zero();
  float coverage = 0.0f;
  // Differential rendering: the catcher's radiance with and without the objects, computed with the
  // same random numbers (identical where no object interferes). Zero unless the sample saw a catcher.
  Rgb with_objects = Rgb::Zero(), without_objects = Rgb::Zero();
  // What the camera ray met first (object or catcher), for the AOV layers: depth is the distance
  // along the unit ray (the render loop turns it into camera-space z); 0: nothing.
  Vec3f normal = Vec3f::Zero();
  Rgb albedo = Rgb::Zero();
  float depth = 0.0f;
};

// The camera ray's first object hit for the integrators that shade only that: fills the sample's
// coverage and AOVs and returns the surface, or nothing on a miss.
inline std::optional<SurfacePoint> first_hit(const EmbreeScene& objects, const Ray& ray, CameraSample& out) {
  const Hit hit = objects.intersect(ray);
  if (!hit.valid()) return std::nullopt;
  const SurfacePoint sp = objects.surface(ray, hit);
  out.coverage = 1.0f;
  out.normal = sp.ns_world;
  out.albedo = sp.material->base_colour(sp.uv);
  out.depth = hit.t;
  return sp;
}

class Integrator {
 public:
  virtual ~Integrator() = default;
  // Must be safe to call from many threads at once.
  virtual CameraSample sample(const Ray& ray, Sampler& sampler) const = 0;
};

}  // namespace insitu
