// The scene file (DESIGN.md "Scene file"): JSON, paths relative to the file, unknown keys are
// errors. parse_scene_file() checks types, ranges and that every named file exists; every error
// names the file and the JSON path. The reference is in README.md.
#pragma once
#include <array>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "camera.h"
#include "cubemap.h"
#include "error.h"
#include "render.h"
#include "tonemap.h"

namespace insitu {

struct CameraSpec {
  enum class Kind { LookAt, Explicit, File, Points } kind = Kind::LookAt;
  std::string where;  // JSON location, for messages
  // LookAt: eye, look, up and one field of view. Explicit: intrinsics (or a field of view) and R, t.
  Vec3d eye = Vec3d::Zero(), look = Vec3d::Zero(), up = Vec3d(0, 1, 0);
  std::optional<double> hfov_deg, vfov_deg;
  std::optional<double> fx, fy, cx, cy;
  Mat3d R_cam_from_world = Mat3d::Identity();
  Vec3d t_cam_from_world = Vec3d::Zero();
  std::string file;  // File: a camera.json
  // Points: calibrate from control points (calibration.h).
  std::string points;
  std::optional<std::string> model;  // "f", "f+c", "f+c+a"; nullopt: auto
  bool bottom_left_origin = false;
};

// One shot: a single file, or exposure brackets (aligned, 8-bit) with their exposure times.
struct ShotSpec {
  std::vector<std::string> files;
  std::vector<double> times_s;       // empty: from EXIF
  std::optional<double> hfov_deg;    // empty: the set's, else EXIF 35 mm focal length, else 90°
  std::string where;
};

struct EnvironmentSpec {
  std::string where;
  std::string image;                 // equirectangular (2:1) or cube strip (1:6) HDR image
  std::array<ShotSpec, 6> shots;     // or six shots, by face (+X, −X, +Y, −Y, +Z, −Z)
  int faced_face = kNegZ;
  std::optional<double> hfov_deg;    // for every shot that does not give its own
  int face_size = 0;                 // 0: natural size of the input
  // Optional parallax correction: the room as a box, and where the environment was captured.
  struct RoomBox {
    Vec3d min = Vec3d::Zero(), max = Vec3d::Zero(), capture = Vec3d::Zero();
  };
  std::optional<RoomBox> room_box;
  // How shots are brought into the photo's radiance unit: auto (EXIF when the photo and every
  // single shot have it, else an estimate that is reported), exif (required), or a factor.
  enum class Exposure { kAuto, kExif, kFactor } exposure = Exposure::kAuto;
  double exposure_factor = 1.0;
  bool from_shots() const { return image.empty(); }
};

struct ObjectSpec {
  std::string where;
  std::string mesh;
  Mat4d M_world_from_object = Mat4d::Identity();
};

// A surface of the local scene: an infinite plane, or a mesh (the real table, a step) placed
// like an object.
struct PlaneSpec {
  Vec3d point = Vec3d::Zero(), normal = Vec3d(0, 1, 0);
  std::optional<ObjectSpec> mesh;  // set: a mesh catcher (point and normal unused)
  bool albedo_from_photo = true;
  Rgb albedo = Rgb::Zero();
};

struct OutputSpec {
  std::string image;   // composite (PNG, JPEG, EXR, TIFF)
  std::string layers;  // multi-layer EXR; empty: none
  ToneMapSettings tonemap;  // for PNG/JPEG; EXR and TIFF stay linear
};

// How the catcher's change is applied to the photo (composite.h).
enum class CompositeMode { kRatio, kAdditive };

struct SceneSpec {
  std::string path;  // the scene file
  std::string photo;
  std::string photo_where;
  CameraSpec camera;
  EnvironmentSpec environment;
  std::vector<PlaneSpec> local_scene;
  std::vector<ObjectSpec> objects;
  RenderSettings render;
  CompositeMode composite = CompositeMode::kRatio;
  OutputSpec output;
  Warnings warnings;  // found while parsing (a rounded rotation, an option without effect)
  // The settings the user gave (scene file or command line), by their scene-file name, e.g.
  // "render.irradiance", "output.tonemap.key": a given setting that has no effect is warned of.
  std::set<std::string> given;
};

SceneSpec parse_scene_file(const std::string& path);

// Outputs whose format ignores the tone map: EXR and TIFF stay linear, scene-referred.
bool is_linear_output(const std::string& image_path);
// A JSON file holding just an environment object (the scene file's "environment" value).
EnvironmentSpec parse_environment_file(const std::string& path);

// Builds the camera for a photo of width x height (not for Kind::Points: see pipeline.cpp).
Camera build_camera(const CameraSpec& spec, int width, int height, Warnings* warnings = nullptr);

// How far a given rotation matrix may be from orthonormal, ‖R Rᵀ − I‖_F, before it is refused;
// within it the nearest rotation is used (exporters round R to about 6 decimals).
constexpr double kRotationTolerance = 1e-3;

// The object transform: translate · rotate · scale (scale first), or a 4x4 matrix.
Mat4d object_transform(const Vec3d& translate, double rotate_deg, const Vec3d& axis, const Vec3d& scale);

}  // namespace insitu
