#include "core/output_paths.h"
#include "core/file_check.h"
#include "scene/scene_file.h"

#include <cmath>
#include <filesystem>
#include <tuple>
#include <fmt/format.h>

#include "calib/calibration.h"
#include "calib/fspy.h"
#include "core/json_reader.h"

namespace insitu {
namespace fs = std::filesystem;

namespace {

std::string resolve(const fs::path& dir, const std::string& rel) {
  const fs::path p(rel);
  return (p.is_absolute() ? p : dir / p).lexically_normal().string();
}

std::string existing_file(const JsonValue& v, const fs::path& dir) {
  const std::string rel = v.string();
  if (rel.empty()) v.fail("empty path");
  const std::string p = resolve(dir, rel);
  std::error_code ec;
  if (!fs::is_regular_file(p, ec) || ec) v.fail(fmt::format("file not found: {}", p));
  return p;
}

std::string output_file(const JsonValue& v, const fs::path& dir, std::initializer_list<const char*> exts) {
  const std::string p = resolve(dir, v.string());
  const std::string ext = lower_extension(p);
  for (const char* e : exts)
    if (ext == e) return p;
  std::string list;
  for (const char* e : exts) list += (list.empty() ? "" : ", ") + std::string(e);
  v.fail(fmt::format("unsupported extension '{}' (use {})", ext, list));
}

int parse_axis(const JsonValue& v) {
  const std::string s = v.string();
  static const char* names[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  for (int f = 0; f < 6; ++f)
    if (s == names[f] || s == face_name(f)) return f;
  v.fail(fmt::format("'{}' is not an axis (+x, -x, +z, -z, up or +y, down or -y)", s));
}

// A camera rotation R (3 rows of 3), checked by checked_rotation (json_reader.h).
Mat3d read_rotation(const JsonValue& v, Warnings* warnings) {
  if (v.size() != 3) v.fail("expected 3 rows of 3 numbers");
  Mat3d R;
  for (std::size_t r = 0; r < 3; ++r) R.row(long(r)) = v.element(r).vec3().transpose();
  return checked_rotation(R, v, warnings);
}

// "camera": {"points": …, "model": …, "origin": …}.
void read_points_camera(const JsonValue& pts, JsonObject& o, const fs::path& dir, CameraSpec& c) {
  c.kind = CameraSpec::Kind::Points;
  c.points = existing_file(pts, dir);
  if (auto m = o.find("model")) {
    const std::string name = m->string();
    if (name != "auto") {
      if (!parse_model(name)) m->fail("expected \"auto\", \"f\", \"f+c\" or \"f+c+a\"");
      c.model = name;
    }
  }
  if (auto origin = o.find("origin")) {
    const auto bottom_left = parse_bottom_left_origin(origin->string());
    if (!bottom_left) origin->fail(std::string("expected ") + kOriginNames);
    c.bottom_left_origin = *bottom_left;
  }
  o.finish();
}

CameraSpec parse_camera(JsonObject o, const fs::path& dir, Warnings& warnings) {
  CameraSpec c;
  c.where = o.where();
  if (auto pts = o.find("points")) {
    read_points_camera(*pts, o, dir, c);
    return c;
  }
  // A camera file of insitu's, or fSpy's export.
  for (const auto& [key, kind] : {std::pair{"file", CameraSpec::Kind::File}, std::pair{"fspy", CameraSpec::Kind::Fspy}})
    if (auto f = o.find(key)) {
      c.kind = kind;
      c.file = existing_file(*f, dir);
      o.finish();
      return c;
    }
  auto read_fov = [&](JsonObject& obj) {
    if (auto h = obj.find("hfov_deg")) c.hfov_deg = h->number(1e-3, 179.0);
    if (auto v = obj.find("vfov_deg")) c.vfov_deg = v->number(1e-3, 179.0);
    if (c.hfov_deg && c.vfov_deg) obj.fail("give hfov_deg or vfov_deg, not both");
  };
  if (o.has("eye")) {
    c.kind = CameraSpec::Kind::LookAt;
    c.eye = o.get("eye").vec3();
    const JsonValue look = o.get("look");
    c.look = look.vec3();
    if (!(c.look - c.eye).allFinite() || !std::isfinite((c.look - c.eye).squaredNorm()))
      look.fail("look − eye overflows a double: the camera's coordinates are too large (use metres near the room)");
    if ((c.look - c.eye).norm() <= 1e-12 * std::max(1.0, c.eye.norm())) look.fail("look point equals the eye");
    if (auto up = o.find("up")) {
      c.up = up->vec3();
      if (c.up.cross(c.look - c.eye).norm() <= 1e-9 * c.up.norm() * (c.look - c.eye).norm())
        up->fail("up is parallel to the viewing direction");
    }
    read_fov(o);
    o.finish();  // an unknown key ("fov") is named before the missing one
    if (!c.hfov_deg && !c.vfov_deg) o.fail("missing hfov_deg or vfov_deg");
    return c;
  }
  c.kind = CameraSpec::Kind::Explicit;
  JsonObject in(o.get("intrinsics"));
  read_fov(in);
  if (c.hfov_deg || c.vfov_deg) {
    if (in.has("fx") || in.has("fy")) in.fail("give a field of view or fx/fy, not both");
  } else {
    c.fx = in.get("fx").number(1e-9, 1e12);
    c.fy = in.find("fy") ? in.get("fy").number(1e-9, 1e12) : *c.fx;
  }
  // The principal point may lie outside the image (a shifted lens), but not absurdly far.
  if (auto cx = in.find("cx")) c.cx = cx->number(-1e7, 1e7);
  if (auto cy = in.find("cy")) c.cy = cy->number(-1e7, 1e7);
  in.finish();
  JsonObject pose(o.get("pose"));
  c.R_cam_from_world = read_rotation(pose.get("R"), &warnings);
  c.t_cam_from_world = pose.get("t").vec3();
  pose.finish();
  o.finish();
  return c;
}

// A shot: "file", ["bracket", "bracket", ...], or {"file" | "files", "times", "hfov_deg",
// "rotate_deg"}.
ShotSpec parse_shot(const JsonValue& v, const fs::path& dir) {
  ShotSpec shot;
  shot.where = v.where();
  auto read_list = [&](const JsonValue& list) {
    if (list.size() < 1) list.fail("expected at least one file");
    for (std::size_t i = 0; i < list.size(); ++i) shot.files.push_back(existing_file(list.element(i), dir));
  };
  if (v.is_string()) {
    shot.files.push_back(existing_file(v, dir));
  } else if (v.is_array()) {
    read_list(v);
  } else {
    JsonObject o(v);
    if (auto f = o.find("file")) {
      if (o.has("files")) o.fail("give 'file' or 'files', not both");
      shot.files.push_back(existing_file(*f, dir));
    } else {
      read_list(o.get("files"));
    }
    if (auto t = o.find("times"))
      for (std::size_t i = 0; i < t->size(); ++i) shot.times_s.push_back(t->element(i).number(1e-9, 1e6));
    if (auto h = o.find("hfov_deg")) shot.hfov_deg = h->number(1.0, 170.0);
    if (auto r = o.find("rotate_deg")) {
      shot.rotate_deg = int(r->integer(0, 270));
      if (shot.rotate_deg % 90 != 0) r->fail("expected 0, 90, 180 or 270 (clockwise)");
    }
    o.finish();
  }
  if (!shot.times_s.empty() && shot.times_s.size() != shot.files.size())
    v.fail(fmt::format("{} times for {} files", shot.times_s.size(), shot.files.size()));
  return shot;
}

// An opening: a rectangle on one wall of the box. One coordinate of min and max equals that
// wall's plane (within 10⁻³ of the box's size, then snapped onto it); the other two span a
// non-empty range inside the wall.
EnvironmentSpec::Opening parse_opening(const JsonValue& v, const EnvironmentSpec::RoomBox& box) {
  JsonObject o(v);
  EnvironmentSpec::Opening op;
  op.min = o.get("min").vec3();
  op.max = o.get("max").vec3();
  o.finish();
  const double tol = 1e-3 * (box.max - box.min).maxCoeff();
  int wall_axis = -1;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(op.max[k] - op.min[k]) > tol) continue;
    for (const double plane : {box.min[k], box.max[k]})
      if (std::abs(op.min[k] - plane) <= tol && std::abs(op.max[k] - plane) <= tol)
        wall_axis = k, op.min[k] = op.max[k] = plane;
  }
  if (wall_axis < 0)
    v.fail("an opening lies on a wall of the box: one coordinate of min and max must equal the box's min or max");
  op.axis = wall_axis;
  for (int k = 0; k < 3; ++k) {
    if (k == wall_axis) continue;
    if (!(op.max[k] > op.min[k])) v.fail("max must exceed min along the wall");
    if (op.min[k] < box.min[k] - tol || op.max[k] > box.max[k] + tol) v.fail("the opening reaches beyond its wall");
  }
  return op;
}

std::vector<EnvironmentSpec::Opening> parse_openings(const JsonValue& v, const EnvironmentSpec::RoomBox& box) {
  if (!v.is_array()) v.fail("expected an array of openings");
  std::vector<EnvironmentSpec::Opening> out;
  for (std::size_t i = 0; i < v.size(); ++i) out.push_back(parse_opening(v.element(i), box));
  return out;
}

EnvironmentSpec::RoomBox parse_room_box(const JsonValue& v) {
  JsonObject b(v);
  EnvironmentSpec::RoomBox box;
  box.min = b.get("min").vec3();
  box.max = b.get("max").vec3();
  const JsonValue cap = b.get("capture");
  box.capture = cap.vec3();
  if (!(box.max.array() > box.min.array()).all()) b.fail("max must exceed min on every axis");
  if (!((box.capture.array() > box.min.array()).all() && (box.capture.array() < box.max.array()).all()))
    cap.fail("the capture point must lie inside the box");
  if (auto ops = b.find("openings")) box.openings = parse_openings(*ops, box);
  b.finish();
  return box;
}

// "faced": the wall the photographer faced when shooting the ceiling and the floor. A missing one
// says what it is (the key's name alone did not).
JsonValue faced_wall(JsonObject& shots) {
  if (!shots.has("faced"))
    shots.fail(
        "missing required key 'faced': the wall you faced when you shot the ceiling and the floor (\"-z\", "
        "\"+x\", ..., or \"front\", ...): the ceiling shot's bottom edge and the floor shot's top edge point "
        "toward it");
  return shots.get("faced");
}

// The walls as "front", "right", "back", "left" plus which world axis "front" faces (right =
// front × up); `shot(face, key)` reads each. Returns the faced wall ("front", ... or an axis).
template <class ReadShot>
int parse_walls_by_turn(JsonObject& s, const ReadShot& shot) {
  const JsonValue fa = s.get("front_axis");
  const int front = parse_axis(fa);
  if (front == kPosY || front == kNegY) fa.fail("front_axis must be horizontal (+x, -x, +z, -z)");
  // Turning right (clockwise seen from above) about +Y: -z -> +x -> +z -> -x -> -z.
  static const int ring[4] = {kNegZ, kPosX, kPosZ, kNegX};
  int k = 0;
  while (ring[k] != front) ++k;
  const int walls[4] = {ring[k], ring[(k + 1) % 4], ring[(k + 2) % 4], ring[(k + 3) % 4]};
  const char* names[4] = {"front", "right", "back", "left"};
  for (int i = 0; i < 4; ++i) shot(walls[i], names[i]);
  const JsonValue faced = faced_wall(s);
  const std::string name = faced.string();
  for (int i = 0; i < 4; ++i)
    if (name == names[i]) return walls[i];
  return parse_axis(faced);
}

EnvironmentSpec parse_environment(const JsonValue& v, const fs::path& dir) {
  EnvironmentSpec e;
  e.where = v.where();
  if (v.is_string()) {
    e.image = existing_file(v, dir);
    return e;
  }
  JsonObject o(v);
  if (auto x = o.find("exposure")) {
    if (x->is_number()) {
      e.exposure = EnvironmentSpec::Exposure::kFactor;
      e.exposure_factor = x->number(1e-12, 1e12);
    } else {
      const std::string s = x->string();
      if (s == "exif")
        e.exposure = EnvironmentSpec::Exposure::kExif;
      else if (s != "auto")
        x->fail("expected \"auto\", \"exif\" or a factor");
    }
  }
  if (auto n = o.find("face_size")) e.face_size = int(n->integer(1, 4096));
  if (auto il = o.find("inverse_lighting")) e.inverse_lighting = il->boolean();
  if (auto r = o.find("register")) {
    const std::string mode = r->string();
    if (mode != "auto" && mode != "none") r->fail("expected \"auto\" or \"none\"");
    e.register_shots = mode == "none" ? EnvironmentSpec::Register::kNone : EnvironmentSpec::Register::kAuto;
  }
  if (auto wb = o.find("white_balance")) {
    const std::string mode = wb->string();
    if (mode != "photo" && mode != "none") wb->fail("expected \"photo\" or \"none\"");
    e.white_balance_to_photo = mode == "photo";
  }
  if (auto rb = o.find("room_box")) e.room_box = parse_room_box(*rb);
  if (auto img = o.find("image")) {
    if (o.has("shots")) o.fail("give 'image' or 'shots', not both");
    e.image = existing_file(*img, dir);
    if (o.has("register")) o.get("register").fail("an image has no shots to register");
    if (auto y = o.find("yaw_deg")) e.yaw_deg = y->number(-360.0, 360.0);
    o.finish();
    return e;
  }
  JsonObject s(o.get("shots"));
  if (auto h = s.find("hfov_deg")) e.hfov_deg = h->number(1.0, 170.0);
  auto shot = [&](int face, const char* key) {
    e.shots[std::size_t(face)] = parse_shot(s.get(key), dir);
    e.shots[std::size_t(face)].key = key;
  };
  if (s.has("front") || s.has("right") || s.has("back") || s.has("left") || s.has("front_axis")) {
    e.faced_face = parse_walls_by_turn(s, shot);
  } else {
    shot(kPosX, "+x");
    shot(kNegX, "-x");
    shot(kPosZ, "+z");
    shot(kNegZ, "-z");
    e.faced_face = parse_axis(faced_wall(s));
  }
  if (e.faced_face == kPosY || e.faced_face == kNegY) s.get("faced").fail("the faced wall must be horizontal");
  // The ceiling and floor shots: "up" and "down", or by their axes "+y" and "-y".
  for (const auto& [face, key, alias] : {std::tuple{kPosY, "up", "+y"}, std::tuple{kNegY, "down", "-y"}}) {
    if (s.has(key) && s.has(alias)) s.fail(fmt::format("give '{}' or '{}', not both", key, alias));
    shot(face, s.has(alias) ? alias : key);
  }
  s.finish();
  o.finish();
  return e;
}

ObjectSpec parse_object(JsonObject o, const fs::path& dir) {
  ObjectSpec obj;
  obj.where = o.where();
  const JsonValue mesh = o.get("mesh");
  obj.mesh = existing_file(mesh, dir);
  if (auto m = o.find("matrix")) {
    if (o.has("translate") || o.has("rotate") || o.has("scale"))
      o.fail("give 'matrix' or translate/rotate/scale, not both");
    obj.M_world_from_object = m->mat4();
    if ((obj.M_world_from_object.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-12)
      m->fail("the last row must be [0, 0, 0, 1] (affine transforms only)");
    const double det = obj.M_world_from_object.topLeftCorner<3, 3>().determinant();
    if (!(std::abs(det) > 1e-300)) m->fail("the matrix is singular");
  } else {
    Vec3d translate = Vec3d::Zero(), axis(0, 1, 0), scale(1, 1, 1);
    double angle_deg = 0;
    if (auto t = o.find("translate")) translate = t->vec3();
    if (auto r = o.find("rotate")) {
      if (r->is_number())
        angle_deg = r->number();
      else if (!r->is_object())
        r->fail("expected degrees about +Y (\"rotate\": 30) or {\"angle_deg\": 30, \"axis\": [x, y, z]}");
      else {
        JsonObject ro(*r);
        angle_deg = ro.get("angle_deg").number();
        if (auto a = ro.find("axis")) {
          axis = a->vec3();
          if (!(axis.norm() > 0)) a->fail("the rotation axis is zero");
        }
        ro.finish();
      }
    }
    if (auto s = o.find("scale")) {
      if (!s->is_number() && !s->is_array()) s->fail("expected a number (uniform: \"scale\": 0.3) or [sx, sy, sz]");
      scale = s->is_number() ? Vec3d::Constant(s->number()) : s->vec3();
      if (!(scale.cwiseAbs().minCoeff() > 0)) s->fail("scale must not be zero");
    }
    obj.M_world_from_object = object_transform(translate, angle_deg, axis, scale);
  }
  o.finish();
  return obj;
}

}  // namespace

Mat4d object_transform(const Vec3d& translate, double rotate_deg, const Vec3d& axis, const Vec3d& scale) {
  Mat4d M = Mat4d::Identity();
  const Mat3d R = Eigen::AngleAxisd(deg_to_rad(rotate_deg), axis.normalized()).toRotationMatrix();
  M.topLeftCorner<3, 3>() = R * scale.asDiagonal();
  M.topRightCorner<3, 1>() = translate;
  return M;
}

EnvironmentSpec parse_environment_file(const std::string& path) {
  const json doc = read_json_file(path);
  return parse_environment(JsonValue(doc, path, "$"), fs::path(path).parent_path());
}

namespace {

// local_scene[i]: {"plane": {point, normal}} or a mesh placed like an object, with an albedo
// ("from_photo", the default, or [r, g, b] in [0, 1]) and optionally a reference mean_albedo.
PlaneSpec parse_local_scene_item(JsonObject item, const fs::path& dir) {
  PlaneSpec plane;
  if (auto a = item.find("albedo")) {
    if (a->is_string()) {
      if (a->string() != "from_photo") a->fail("expected \"from_photo\" or [r, g, b]");
    } else {
      const Vec3d rgb = a->vec3();
      if (rgb.minCoeff() < 0 || rgb.maxCoeff() > 1) a->fail("albedo must lie in [0, 1]");
      plane.albedo_from_photo = false;
      plane.albedo = rgb.cast<float>().array();
    }
  }
  // A reference for inverse lighting: the surface's mean albedo, its texture kept.
  if (auto m = item.find("mean_albedo")) {
    if (!plane.albedo_from_photo) m->fail("give 'albedo' (uniform, rendered) or 'mean_albedo' (a reference), not both");
    plane.mean_albedo = m->number(0.001, 1.0);
  }
  if (item.has("mesh")) {
    if (item.has("plane")) item.fail("give 'plane' or 'mesh', not both");
    plane.mesh = parse_object(std::move(item), dir);  // checks the remaining keys
    return plane;
  }
  JsonObject pl(item.get("plane"));
  plane.point = pl.get("point").vec3();
  const JsonValue n = pl.get("normal");
  plane.normal = n.vec3();
  if (!(plane.normal.norm() > 0)) n.fail("the normal is zero");
  plane.normal.normalize();
  pl.finish();
  item.finish();
  return plane;
}

// references[i].sphere: {"center": [x, y, z], "radius": r}, in the world frame, metres.
BallSpec parse_ball(JsonObject sphere) {
  BallSpec ball;
  ball.center_world = sphere.get("center").vec3();
  ball.radius_m = sphere.get("radius").number(1e-6, 1e6);
  sphere.finish();
  return ball;
}

// references[i].polygon_px: [[u, v], ...], 3 or more corners, a simple polygon of positive area.
std::vector<Vec2d> parse_polygon(const JsonValue& poly) {
  if (poly.size() < 3) poly.fail("a polygon needs 3 or more [u, v] corners");
  std::vector<Vec2d> polygon_px;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const JsonValue corner = poly.element(i);
    if (corner.size() != 2) corner.fail("expected [u, v] in pixels");
    polygon_px.emplace_back(corner.element(0).number(-1e9, 1e9), corner.element(1).number(-1e9, 1e9));
  }
  // The shoelace formula: twice the signed area.
  double twice_area = 0;
  for (std::size_t i = 0; i < polygon_px.size(); ++i) {
    const Vec2d& a = polygon_px[i];
    const Vec2d& b = polygon_px[(i + 1) % polygon_px.size()];
    twice_area += a.x() * b.y() - b.x() * a.y();
  }
  if (!(std::abs(twice_area) >= 2.0)) poly.fail("the polygon covers less than one pixel");
  return polygon_px;
}

// references[i]: {"polygon_px": [...]} or {"sphere": {...}}, "albedo": a, and optionally "photo":
// a reference plate. The photo's size is checked when it is read (pipeline.cpp), the plate's when
// inverse lighting reads it (light_recovery.cpp).
ReferenceSpec parse_reference(JsonObject item, const fs::path& dir) {
  ReferenceSpec ref;
  ref.where = item.where();
  auto poly = item.find("polygon_px");
  auto sphere = item.find("sphere");
  if (poly && sphere)
    sphere->fail("give 'polygon_px' (a patch in the photo) or 'sphere' (a ball in the room), not both");
  if (!poly && !sphere) item.fail("expected 'polygon_px' (a patch in the photo) or 'sphere' (a ball in the room)");
  if (poly) ref.polygon_px = parse_polygon(*poly);
  if (sphere) ref.ball = parse_ball(JsonObject(*sphere));
  if (auto plate = item.find("photo")) ref.photo = existing_file(*plate, dir);
  ref.albedo = item.get("albedo").number(0.001, 1.0);
  item.finish();
  return ref;
}

// The render loop's keys; the rest are the integrators', read by them (src/integrators/registry.h).
void parse_render(const JsonValue& r, RenderSpec& render) {
  JsonObject ro(r);
  if (auto in = ro.find("integrator")) render.integrator = in->string();
  if (auto spp = ro.find("spp")) render.spp = int(spp->integer(1, kMaxSpp));
  if (auto seed = ro.find("seed")) render.seed = std::uint64_t(seed->integer(0, kMaxSeed));
  if (auto t = ro.find("noise_target")) render.noise_target = t->number(0, 1);
  render.block = {r.raw(), r.file(), r.path()};
}

// output.tonemap: "name", or {"op": "name", "key": k, "bias": b}.
void parse_tonemap_settings(const JsonValue& tm, SceneSpec& scene) {
  auto parse_op = [&](const JsonValue& v) {
    const auto op = parse_tonemap(v.string());
    if (!op) v.fail("expected " + quoted_choices(names_of(kToneMaps)));
    scene.output.tonemap.op = *op;
  };
  scene.given.insert("output.tonemap");
  if (tm.is_string()) return parse_op(tm);
  JsonObject t(tm);
  parse_op(t.get("op"));
  if (auto k = t.find("key")) scene.output.tonemap.key = k->number(1e-6, 1e6), scene.given.insert("output.tonemap.key");
  if (auto b = t.find("bias"))
    scene.output.tonemap.bias = b->number(0.01, 0.99), scene.given.insert("output.tonemap.bias");
  t.finish();
}

// output: the composite (default out/composite.png), the layers (out/layers.exr with the default
// image; beside a given image, IMAGE_STEM.layers.exr; or "none").
void parse_output(const std::optional<JsonValue>& out, const fs::path& dir, SceneSpec& scene) {
  scene.output.image = resolve(dir, "out/composite.png");
  scene.output.layers = resolve(dir, "out/layers.exr");
  if (!out) return;
  JsonObject oo(*out);
  if (auto img = oo.find("image")) {
    scene.output.image = output_file(*img, dir, {".png", ".jpg", ".jpeg", ".exr", ".tif", ".tiff"});
    scene.output.layers = layers_path_for(scene.output.image);
  }
  if (auto layers = oo.find("layers"))
    scene.output.layers = layers->is_string() && layers->string() == "none" ? "" : output_file(*layers, dir, {".exr"});
  if (auto tm = oo.find("tonemap")) parse_tonemap_settings(*tm, scene);
  oo.finish();
}

}  // namespace

std::string layers_path_for(const std::string& image_path) {
  const fs::path p(image_path);
  return (p.parent_path() / (p.stem().string() + ".layers.exr")).string();
}

SceneSpec parse_scene_file(const std::string& path) {
  return parse_scene_json(read_json_file(path), path, fs::path(path).parent_path().string());
}

SceneSpec parse_scene_json(const json& doc, const std::string& path, const std::string& base_dir) {
  const fs::path dir(base_dir);
  SceneSpec scene;
  scene.path = path;
  scene.render.block.file = path;
  JsonObject root(JsonValue(doc, path, "$"));

  const JsonValue photo = root.get("photo");
  scene.photo = existing_file(photo, dir);
  scene.photo_where = photo.where();
  scene.camera = parse_camera(JsonObject(root.get("camera")), dir, scene.warnings);
  scene.environment = parse_environment(root.get("environment"), dir);
  if (auto ls = root.find("local_scene"))
    for (std::size_t i = 0; i < ls->size(); ++i)
      scene.local_scene.push_back(parse_local_scene_item(JsonObject(ls->element(i)), dir));
  if (auto refs = root.find("references"))
    for (std::size_t i = 0; i < refs->size(); ++i)
      scene.references.push_back(parse_reference(JsonObject(refs->element(i)), dir));
  if (auto objs = root.find("objects"))
    for (std::size_t i = 0; i < objs->size(); ++i)
      scene.objects.push_back(parse_object(JsonObject(objs->element(i)), dir));
  if (auto r = root.find("render")) parse_render(*r, scene.render);
  if (auto c = root.find("composite")) {
    const auto mode = parse_name(kCompositeModes, c->string());
    if (!mode) c->fail("expected " + quoted_choices(names_of(kCompositeModes)));
    scene.composite = *mode;
  }
  if (auto d = root.find("denoise")) scene.denoise = d->boolean();
  parse_output(root.find("output"), dir, scene);
  root.finish();
  return scene;
}

bool is_linear_output(const std::string& image_path) {
  const std::string ext = lower_extension(image_path);
  return ext == ".exr" || ext == ".tif" || ext == ".tiff";
}

Camera build_camera(const CameraSpec& c, int width, int height, Warnings* warnings) {
  if (c.kind == CameraSpec::Kind::LookAt) {
    const double hfov =
        c.hfov_deg ? *c.hfov_deg : rad_to_deg(2 * std::atan(std::tan(0.5 * deg_to_rad(*c.vfov_deg)) * width / height));
    return Camera::look_at(c.eye, c.look, c.up, hfov, width, height);
  }
  if (c.kind == CameraSpec::Kind::Fspy) return camera_from_fspy(c.file, width, height, warnings);
  Camera cam;
  cam.width = width;
  cam.height = height;
  if (c.kind == CameraSpec::Kind::File) {
    const json doc = read_json_file(c.file);
    JsonObject o(JsonValue(doc, c.file, "$"));
    const long w = o.get("width").integer(1, 1 << 20), h = o.get("height").integer(1, 1 << 20);
    if (w != width || h != height)
      throw InputError(c.file + ":$.width",
                       fmt::format("camera is for {}x{} images, the photo is {}x{}", w, h, width, height));
    // camera.json: intrinsics and pose define the camera; eye/look/up and the fields of view
    // are there for people and are recomputed from them.
    JsonObject in(o.get("intrinsics"));
    cam.fx = in.get("fx").number(1e-9, 1e12);
    cam.fy = in.get("fy").number(1e-9, 1e12);
    cam.cx = in.get("cx").number();
    cam.cy = in.get("cy").number();
    in.finish();
    JsonObject pose(o.get("pose"));
    cam.R_cam_from_world = read_rotation(pose.get("R"), warnings);
    cam.t_cam_from_world = pose.get("t").vec3();
    pose.finish();
    for (const char* informational : {"eye", "look", "up", "hfov_deg", "vfov_deg", "calibration"})
      o.find(informational);
    o.finish();
    return cam;
  }
  if (c.fx) {
    cam.fx = *c.fx;
    cam.fy = c.fy ? *c.fy : *c.fx;
  } else if (c.hfov_deg) {
    cam.fx = cam.fy = 0.5 * width / std::tan(0.5 * deg_to_rad(*c.hfov_deg));
  } else {
    cam.fx = cam.fy = 0.5 * height / std::tan(0.5 * deg_to_rad(*c.vfov_deg));
  }
  cam.cx = c.cx ? *c.cx : 0.5 * width;
  cam.cy = c.cy ? *c.cy : 0.5 * height;
  cam.R_cam_from_world = c.R_cam_from_world;
  cam.t_cam_from_world = c.t_cam_from_world;
  // Finite, but almost surely not meant: a focal length that opens the view to nearly 180°.
  if (warnings && cam.hfov_deg() > 170.0)
    warnings->add(c.where + ".intrinsics",
                  fmt::format("fx = {:g} px gives a horizontal field of view of {:.1f}°: is fx in "
                              "pixels (not millimetres)?",
                              cam.fx, cam.hfov_deg()));
  return cam;
}

EnvironmentSpec environment_from_argument(const std::string& path, std::string* photo) {
  if (lower_extension(path) == ".json") {
    // A scene file (it has a photo), or a file holding just an environment object.
    if (!read_json_file(path).contains("photo")) return parse_environment_file(path);
    const SceneSpec scene = parse_scene_file(path);
    if (photo) *photo = scene.photo;
    return scene.environment;
  }
  require_existing(path);
  EnvironmentSpec spec;
  spec.image = path;
  return spec;
}

}  // namespace insitu
