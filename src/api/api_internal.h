// The C API's handles and its one error boundary (include/insitu/insitu.h). Every exported
// function runs its body through `guarded`: an InputError becomes INSITU_ERROR_INPUT with its
// `where: what`, an ApiMisuse INSITU_ERROR_ARGUMENT, anything else INSITU_ERROR_INTERNAL; the
// message is kept per thread for insitu_last_error(). Nothing thrown crosses the API.
#pragma once
#include <atomic>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <insitu/insitu.h>  // the public header, from include/
#include "scene/output_layers.h"
#include "scene/pipeline.h"

struct insitu_scene {
  insitu::json doc;                                      // the scene file as JSON, as insitu_scene_set changed it
  std::string name, base_dir;                            // for messages; where relative paths start
  insitu::SceneSpec spec;                                // parsed from doc, with the overrides below
  std::optional<std::vector<insitu::PointSpec>> points;  // insitu_scene_set_control_points
  std::optional<std::string> points_model;
  std::optional<std::pair<int, int>> camera_size;     // insitu_scene_set_camera's, checked at load
  std::vector<insitu::Mesh> memory_meshes;            // placed
  insitu::Warnings mesh_warnings;                     // theirs (degenerate triangles dropped)
  std::shared_ptr<const insitu::LoadedScene> loaded;  // null: to be (re)loaded
  std::string warnings_text, calibration_text;
  std::atomic<bool> cancel{false};
};

struct insitu_result {
  std::shared_ptr<const insitu::LoadedScene> scene;
  insitu::RenderResult result;
  std::vector<insitu::OutputLayer> layers;
  std::string report;
};

struct insitu_calibration {
  std::vector<insitu::ControlPoint> points;
  insitu::CalibrationResult result;
  std::vector<std::pair<std::string, std::vector<insitu::NamedPoint>>> boxes;
  std::string report, json, blender;
};

namespace insitu::api {

// A caller's mistake that is not bad input: a null handle, an unknown layer, a short buffer.
struct ApiMisuse : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

void set_last_error(const std::string& message);

template <class F>
insitu_status guarded(F&& body) noexcept {
  try {
    body();
    return INSITU_OK;
  } catch (const InputError& e) {
    set_last_error(e.what());
    return INSITU_ERROR_INPUT;
  } catch (const ApiMisuse& e) {
    set_last_error(e.what());
    return INSITU_ERROR_ARGUMENT;
  } catch (const std::exception& e) {
    set_last_error(std::string("internal error: ") + e.what());
    return INSITU_ERROR_INTERNAL;
  } catch (...) {
    set_last_error("internal error: unknown exception");
    return INSITU_ERROR_INTERNAL;
  }
}

// The pointer itself, for C strings and arrays.
template <class T>
const T* not_null(const T* p, const char* what) {
  if (!p) throw ApiMisuse(std::string(what) + " is NULL");
  return p;
}

template <class T>
T& require(T* handle, const char* what) {
  if (!handle) throw ApiMisuse(std::string(what) + " is NULL");
  return *handle;
}

// The scene's spec from its JSON and overrides (throws InputError, the scene unchanged), and the
// loaded scene, (re)loaded when something changed.
void reparse(insitu_scene& scene, json doc);
const LoadedScene& loaded(insitu_scene& scene);

}  // namespace insitu::api
