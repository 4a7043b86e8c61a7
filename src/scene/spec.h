// The scene file's plain spec types (DESIGN.md "Scene file"): what the parser (scene_file.h)
// builds from the JSON and the pipeline (pipeline.h) turns into objects. Nothing of the render
// side: a spec names files and settings, it loads and builds nothing.
#pragma once
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/json_reader.h"
#include "core/math.h"
#include "light/environment_spec.h"
#include "output/settings.h"

namespace insitu {

// A control point handed over in memory (the C API), not read from a file.
struct PointSpec {
  Vec2d uv_px = Vec2d::Zero();  // top-left origin
  Vec3d p_world = Vec3d::Zero();
};

struct CameraSpec {
  enum class Kind { LookAt, Explicit, File, Fspy, Points } kind = Kind::LookAt;
  std::string where;  // JSON location, for messages
  // LookAt: eye, look, up and one field of view. Explicit: intrinsics (or a field of view) and R, t.
  Vec3d eye = Vec3d::Zero(), look = Vec3d::Zero(), up = Vec3d(0, 1, 0);
  std::optional<double> hfov_deg, vfov_deg;
  std::optional<double> fx, fy, cx, cy;
  Mat3d R_cam_from_world = Mat3d::Identity();
  Vec3d t_cam_from_world = Vec3d::Zero();
  std::string file;  // File: a camera.json; Fspy: the JSON fSpy exports (calib/fspy.h)
  // Points: calibrate from control points (calibration.h).
  std::string points;
  std::vector<PointSpec> point_list;  // given in memory (the C API): used in place of the file
  std::optional<std::string> model;   // "f", "f+c", "f+c+a"; nullopt: auto
  bool bottom_left_origin = false;
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
  // Inverse lighting's reference: the surface's albedo on average over the photo's pixels of it
  // (its luminance), while it is still rendered with the photo's own texture.
  std::optional<double> mean_albedo;
};

// A grey ball in the room, seen in the photo: its centre in the world frame and its radius, metres.
struct BallSpec {
  Vec3d center_world = Vec3d::Zero();
  double radius_m = 0;
};

// Something of known albedo in the photo, inverse lighting's reference (relight/inverse_lighting.h):
// a white sheet (≈ 0.8) or a grey card (0.18) lying on a real surface, drawn as a polygon in photo
// pixels (top-left origin); or a grey ball, which sees the light from many directions.
struct ReferenceSpec {
  std::string where;              // JSON location, for messages
  std::vector<Vec2d> polygon_px;  // empty for a ball
  std::optional<BallSpec> ball;
  double albedo = 0;  // luminance
  // A reference plate: the reference photographed from the photo's camera, with the same exposure,
  // so that the photo itself can stay clean (a ball taken away before the photo). Empty: the photo.
  std::string photo;
};

struct OutputSpec {
  std::string image;        // composite (PNG, JPEG, EXR, TIFF)
  std::string layers;       // multi-layer EXR; empty: none
  ToneMapSettings tonemap;  // for PNG/JPEG; EXR and TIFF stay linear
};

// The render stage: the render loop's samples per pixel, seed and noise target (adaptive sampling,
// render/adaptive.h; 0: off, spp then a fixed count rather than a cap), the integrator's name, and the
// render object itself, whose other keys are the integrators' parameters (render.max_depth, or
// render.path.max_depth): each integrator reads its own (src/integrators/registry.h).
struct RenderSpec {
  std::string integrator = "realtime";
  int spp = 16;
  std::uint64_t seed = 1;
  double noise_target = 0;
  JsonBlock block{json::object(), "", "$.render"};
};

// The ranges every verb and the scene file accept for samples per pixel and the seed.
constexpr int kMaxSpp = 1 << 20;
constexpr long kMaxSeed = (1L << 62) - 1;

struct SceneSpec {
  std::string path;  // the scene file
  std::string photo;
  std::string photo_where;
  CameraSpec camera;
  EnvironmentSpec environment;
  std::vector<PlaneSpec> local_scene;
  std::vector<ReferenceSpec> references;
  std::vector<ObjectSpec> objects;
  RenderSpec render;
  CompositeMode composite = CompositeMode::kRatio;
  bool denoise = false;  // the composite denoised (output/denoise.h); the layers stay as rendered
  OutputSpec output;
  Warnings warnings;  // found while parsing (a rounded rotation, an option without effect)
  // The settings the user gave (scene file or command line), by their scene-file name, e.g.
  // "render.irradiance", "output.tonemap.key": a given setting that has no effect is warned of.
  std::set<std::string> given;
};

}  // namespace insitu
