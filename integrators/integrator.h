// The integrator interface and its registry. One integrator per file in integrators/, each
// opening with a comment that documents its parameters; registry.cpp maps names to factories in
// a plain table (no static-initialization tricks).
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "camera.h"
#include "cubemap.h"
#include "embree_scene.h"
#include "irradiance.h"
#include "sampler.h"

namespace insitu {

// What an integrator may use: the objects, and the room's light as a radiance cube.
// A plane of the local scene (the real floor): catches the objects' shadows and bounce light.
struct CatcherPlane {
  Vec3f point, normal;               // unit normal, on the side the camera sees
  bool albedo_from_photo = true;
  Rgb albedo = Rgb::Zero();
  Rgb irradiance = Rgb::Zero();      // E(normal) of the environment without objects (exact)
};

struct CatcherMesh {
  bool albedo_from_photo = true;
  Rgb albedo = Rgb::Zero();
};

struct RenderInputs {
  const EmbreeScene* objects = nullptr;
  const CubeMap* environment = nullptr;
  std::vector<CatcherPlane> planes;     // the local scene: planes
  const EmbreeScene* catcher_meshes = nullptr;           // and meshes
  std::vector<CatcherMesh> catcher_mesh_info;            // by mesh index
  const IrradianceField* catcher_irradiance = nullptr;   // E(n) without objects, for the meshes
  const Image* photo_linear = nullptr;  // the real room as the camera saw it
  // Parallax correction of environment lookups (path): the room box and the capture point.
  bool room_box = false;
  Vec3f box_min = Vec3f::Zero(), box_max = Vec3f::Zero(), capture = Vec3f::Zero();
  const Camera* camera = nullptr;
  IrradianceMode irradiance_mode = IrradianceMode::kExact;  // for integrators that use one
  int max_depth = 5;                                         // bounces, for `path`
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

// What an integrator reads of the scene beyond the objects and the cube: a setting it does not
// read has no effect, and the pipeline says so when the user gives it.
struct IntegratorCapabilities {
  bool local_scene = false;      // catches shadows on local_scene (differential rendering)
  bool room_box = false;         // uses environment.room_box
  bool irradiance_mode = false;  // reads render.irradiance
  bool max_depth = false;        // reads render.max_depth
};

struct IntegratorEntry {
  const char* name;
  const char* summary;
  std::unique_ptr<Integrator> (*create)(const RenderInputs& inputs);
  IntegratorCapabilities uses;
};

const std::vector<IntegratorEntry>& integrator_registry();
// The entry named `name`, or nullptr.
const IntegratorEntry* find_integrator(const std::string& name);
// Throws InputError naming the known integrators when `name` is not one of them.
std::unique_ptr<Integrator> make_integrator(const std::string& name, const RenderInputs& inputs);
bool is_integrator(const std::string& name);
// "unknown integrator 'x' (known: realtime, irradiance, path)".
std::string unknown_integrator_message(const std::string& name);

}  // namespace insitu
