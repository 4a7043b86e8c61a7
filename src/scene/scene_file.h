// The scene file (DESIGN.md "Scene file"): JSON, paths relative to the file, unknown keys are
// errors. parse_scene_file() checks types, ranges and that every named file exists; every error
// names the file and the JSON path. The reference is docs/scene-file.md.
#pragma once
#include <string>

#include "core/camera.h"
#include "core/error.h"
#include "scene/spec.h"

namespace insitu {

SceneSpec parse_scene_file(const std::string& path);
// A scene held in memory (the C API's insitu_scene_from_json): `path` names it in messages and
// relative paths in it are resolved against `base_dir` ("" : the working directory).
SceneSpec parse_scene_json(const json& doc, const std::string& path, const std::string& base_dir);

// Outputs whose format ignores the tone map: EXR and TIFF stay linear, scene-referred.
bool is_linear_output(const std::string& image_path);
// The layers that go with an image (-o, or a scene file's output.image without output.layers):
// IMAGE_STEM.layers.exr beside it, so that scenes and batch entries with images of their own do
// not write one out/layers.exr over each other's.
std::string layers_path_for(const std::string& image_path);
// A JSON file holding just an environment object (the scene file's "environment" value).
EnvironmentSpec parse_environment_file(const std::string& path);

// An environment named on the command line: a scene file (its environment), a JSON file holding
// just an environment object (e.g. {"shots": {...}}), or an HDR image. For a scene file, *photo
// receives its photo's path.
EnvironmentSpec environment_from_argument(const std::string& path, std::string* photo = nullptr);

// Builds the camera for a photo of width x height (not for Kind::Points: see pipeline.cpp).
Camera build_camera(const CameraSpec& spec, int width, int height, Warnings* warnings = nullptr);

// The object transform: translate · rotate · scale (scale first), or a 4x4 matrix.
Mat4d object_transform(const Vec3d& translate, double rotate_deg, const Vec3d& axis, const Vec3d& scale);

}  // namespace insitu
