// The render pipeline of a scene file, stage by stage: load (photo, camera, environment,
// objects), render the layers, composite over the photo, write the outputs.
#pragma once
#include <memory>

#include "calibration.h"
#include "camera.h"
#include "cubemap.h"
#include "embree_scene.h"
#include "environment.h"
#include "error.h"
#include "image.h"
#include "render.h"
#include "scene.h"

namespace insitu {

struct LoadedScene {
  SceneSpec spec;
  ImageFile photo;
  Image photo_linear;
  Camera camera;
  std::optional<CalibrationResult> calibration;  // when the camera came from control points
  CubeMap environment;
  EnvironmentInfo environment_info;
  std::unique_ptr<EmbreeScene> objects;
  std::unique_ptr<EmbreeScene> catcher_meshes;  // meshes of the local scene
  Warnings warnings;
  double load_seconds = 0;
};

LoadedScene load_scene(const SceneSpec& spec);

struct RenderResult {
  double prepare_seconds = 0;  // the integrator's precomputation (legacy blur, irradiance cube)
  RenderLayers layers;
  Image composite_linear;
  Image composite_encoded;  // what goes into a PNG/JPEG
};

RenderResult render_scene(const LoadedScene& scene, const ProgressFn& progress = {});

// Writes the composite image and the layered EXR, each atomically.
void write_outputs(const LoadedScene& scene, const RenderResult& result);

}  // namespace insitu
