// The render pipeline of a scene file, stage by stage: load (photo, camera, environment,
// objects), render the layers, composite over the photo, write the outputs.
#pragma once
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>

#include "calib/calibration.h"
#include "calib/object_uncertainty.h"
#include "core/camera.h"
#include "light/cubemap.h"
#include "render/embree_scene.h"
#include "light/room_cache.h"
#include "light/environment.h"
#include "core/error.h"
#include "core/image.h"
#include "core/output_paths.h"
#include "relight/inverse_lighting.h"
#include "relight/photo_fill.h"
#include "relight/photo_white_balance.h"
#include "relight/unseen_outside.h"
#include "render/render.h"
#include "integrators/registry.h"
#include "scene/scene_file.h"

namespace insitu {

struct LoadedScene {
  SceneSpec spec;
  ImageFile photo;
  Image photo_linear;
  Camera camera;
  std::optional<CalibrationResult> calibration;       // when the camera came from control points
  std::vector<ObjectUncertainty> object_uncertainty;  // the calibration's, at each object's corners
  std::optional<ClickHint> click_hint;                // where one more click would help them most
  CubeMap environment;
  EnvironmentInfo environment_info;
  std::optional<RoomBox> room;                            // environment.room_box, for the renderer
  std::optional<WhiteBalance> white_balance;              // the light's, to the photo (light_recovery.h)
  std::optional<PhotoFill> photo_fill;                    // the uncovered directions (light_recovery.h)
  std::optional<InverseLightingResult> inverse_lighting;  // when shots clipped (light_recovery.h)
  std::optional<UnseenOutsideFit> unseen_outside;         // in a room box with openings (light_recovery.h)
  std::shared_ptr<RoomCache> room_cache;                  // the room's prepared light and grids (room_cache.h), shared
  std::unique_ptr<EmbreeScene> objects;
  std::unique_ptr<EmbreeScene> catcher_meshes;  // meshes of the local scene
  ResolvedIntegrator integrator;                // the entry and its parameters, read from the render object
  Warnings warnings;
  Warnings room_warnings;  // those of loading the room (what a scene sharing it repeats)
  double load_seconds = 0;
};

// Refuses (InputError) before reading anything when an output would replace an input or another
// output (output_paths.h), and again once the meshes have named their MTL files and textures.
// `memory_objects`: meshes given in memory (the C API), already placed, after the spec's objects.
// `room`: a scene loaded already whose room (photo, camera, environment, room box, recovered
// light) this one shares, not read again (a batch's entries: the caller checks that the room's
// settings are the same). `stop` (core/stop.h) is looked at between the stages (the photo, the
// environment, the camera, the recovered light, each mesh) and within inverse lighting: once set,
// load_scene throws Stopped.
LoadedScene load_scene(const SceneSpec& spec, std::vector<Mesh> memory_objects = {}, const LoadedScene* room = nullptr,
                       const std::atomic<bool>* stop = nullptr);

// The photo and its camera as load_scene reads them before the environment, which they anchor
// when six handheld shots have no room box (light/photo_anchor.h); the calibration's warnings go
// to `warnings`. Throws InputError as load_scene would.
struct PhotoAndCamera {
  ImageFile photo;
  Camera camera;
};
PhotoAndCamera load_photo_and_camera(const SceneSpec& spec, Warnings& warnings);

// Every corner of each reference polygon lies within a photo of width x height pixels (InputError
// naming references[i].polygon_px[j]); load_scene checks it, and the studio before it saves one.
void check_references(const SceneSpec& spec, int width, int height);

// The files a scene reads (before loading its meshes) and writes.
std::vector<NamedPath> scene_input_files(const SceneSpec& spec);
// scene_input_files and, for each mesh, the MTL files and textures it will read (render/mesh.h's
// obj_dependencies, named "read by <mesh>" as after loading): known before anything is loaded.
std::vector<NamedPath> scene_input_files_with_meshes(const SceneSpec& spec);
std::vector<NamedPath> scene_output_files(const SceneSpec& spec);

struct RenderResult {
  double prepare_seconds = 0;  // the integrator's precomputation (legacy blur, irradiance cube)
  RenderLayers layers;
  Image composite_linear;
  Image composite_encoded;               // what goes into a PNG/JPEG
  bool denoise_asked = false;            // denoises() held for this result
  bool denoised = false;                 // the composite went through output/denoise.h (the layers never do)
  double denoise_seconds = 0;            // its time, after the render's
  int denoise_block = 0;                 // the denoiser's block size, s × s pixels (output/denoise.h)
  std::size_t denoise_pixels_alone = 0;  // of them, the pixels fitted one by one
};

// How a render may be stopped and resumed: `stop` ends it after the pass under way;
// `state` starts it from a checkpoint (render/checkpoint.h) and receives where it ended. A part of
// a split render takes only the samples [sample_begin, sample_end) of render.spp (end
// −1: spp). `stop_at_once`: RenderSettings::stop_at_once, and the stop is looked at during the
// integrator's preparation too (RenderInputs::stop), which then throws Stopped (core/stop.h).
struct RenderControl {
  const std::atomic<bool>* stop = nullptr;
  RenderState* state = nullptr;
  int sample_begin = 0, sample_end = -1;
  bool stop_at_once = false;
};
RenderResult render_scene(const LoadedScene& scene, const ProgressFn& progress = {}, const RenderControl& control = {});
// Whether finish_render denoises: when asked (unset: the scene's `denoise`) and the scene's
// integrator is Monte Carlo; the others' images have no noise, and the studio's legacy A/B must
// show the legacy image as it is.
bool denoises(const LoadedScene& scene, std::optional<bool> denoise);
// The composite of layers rendered (or merged from parts) for this scene.
// `denoise`: whether the composite is denoised (output/denoise.h; see denoises). It is not where
// no pixel has two samples: the denoiser weighs its neighbours by the noise it estimates from the
// spread of a pixel's samples, which one sample does not have (the composite would come back as
// it went in, a second later).
RenderResult finish_render(const LoadedScene& scene, RenderLayers layers, double prepare_seconds = 0,
                           std::optional<bool> denoise = std::nullopt);

// What a checkpoint must match to be resumed: a 64-bit FNV-1a hash of everything the render's
// sums depend on — the camera, spp, seed, the integrator and its parameters, the photo and the
// environment as loaded, the local scene, the room box and the meshes. Not the outputs' names, the
// tone map or the composite's form, which act after the sums.
std::uint64_t render_fingerprint(const LoadedScene& scene);

// Writes the layered EXR (scene/output_layers.h), the composite image and the JSON report to the
// scene's outputs or to `output`'s (checked first against every input), all or none: each is
// written and verified under a temporary name, and the three are renamed only when all are
// (core/staged_writes.h). The report is renamed last: where it exists, the image and the layers
// are whole (a batch's mark of an entry done). `report_extra`: keys added to the report (a batch entry's).
void write_outputs(const LoadedScene& scene, const RenderResult& result, const OutputSpec* output = nullptr,
                   const nlohmann::json& report_extra = {});

// The report written next to the image (IMAGE_STEM.report.json): stage timings, the calibration's
// RMS, the integrator, irradiance mode, samples per pixel, noise estimate, non-finite samples, and
// per shot the coverage and clipped percentage.
nlohmann::json render_report(const LoadedScene& scene, const RenderResult& result, const OutputSpec* output = nullptr);
// The report of an image: its whole name + ".report.json" (a.png and a.exr keep their own).
std::string report_path(const std::string& image_path);

// Whether a world-space box lies entirely outside the camera's view frustum (conservative: a box
// that straddles a corner of the frustum may still be out of view).
bool outside_view(const Camera& camera, const Bounds& box_world);

// Settings given (SceneSpec::given, the local scene, the room box) that the integrator or the
// output format does not use, each named in a warning; and what is really done, for the report.
// (The integrators' parameters are checked by resolve_integrator.)
void warn_ineffective_settings(const SceneSpec& spec, const ResolvedIntegrator& integrator, Warnings& warnings);
std::string effective_tonemap(const SceneSpec& spec);  // "none" for EXR/TIFF

}  // namespace insitu
