#include "scene/pipeline.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <fmt/format.h>

#include "core/output_paths.h"
#include "core/stop.h"
#include "core/text_file.h"
#include "light/irradiance.h"
#include "output/composite.h"
#include "output/denoise.h"
#include "output/tonemap.h"
#include "render/checkpoint.h"
#include "render/gltf_mesh.h"
#include "render/mesh.h"
#include "scene/light_recovery.h"
#include "scene/shots_report.h"

namespace insitu {

std::string effective_tonemap(const SceneSpec& spec) {
  return is_linear_output(spec.output.image) ? "none" : tonemap_name(spec.output.tonemap.op);
}

void warn_ineffective_settings(const SceneSpec& spec, const ResolvedIntegrator& integrator, Warnings& w) {
  const IntegratorEntry& e = *integrator.entry;
  const bool volume = integrator.params.value("irradiance", "") == "volume";
  const std::string by = "the " + spec.render.integrator + " integrator";
  auto given = [&](const char* name) { return spec.given.count(name) > 0; };
  if (!spec.local_scene.empty() && !e.uses.local_scene)
    w.add("local_scene", "has no effect: " + by + " draws no shadows on it (only path does)");
  if (spec.environment.room_box && !e.uses.room_box && !volume)
    w.add("environment.room_box",
          "has no effect: " + by + " looks the cube up by direction only (path and irradiance's volume mode use it)");
  if (spec.denoise && !e.uses.monte_carlo)
    w.add("denoise", "has no effect: " + by + " is not Monte Carlo, its image has no noise to remove");
  const ToneMap op = spec.output.tonemap.op;
  if (is_linear_output(spec.output.image)) {
    for (const char* key : {"output.tonemap", "output.tonemap.key", "output.tonemap.bias"})
      if (given(key))
        w.add(key, "has no effect: " + spec.output.image +
                       " is a linear, scene-referred image; tone mapping applies to PNG and JPEG");
    return;
  }
  if (given("output.tonemap.key") && !reads_key(op))
    w.add("output.tonemap.key", "has no effect with the photo tone map (it re-encodes through the photo's own curve)");
  if (given("output.tonemap.bias") && !reads_bias(op))
    w.add("output.tonemap.bias",
          std::string("has no effect with the ") + tonemap_name(op) + " tone map (only adaptive_log has a bias)");
}

// A transform that shrinks a mesh below float resolution (scale 1e-30) leaves nothing to render.
void warn_if_collapsed(const Mesh& mesh, const std::string& where, Warnings& warnings) {
  const Bounds b = mesh_bounds(mesh);
  if ((b.lo.array() <= b.hi.array()).all() && !((b.hi - b.lo).maxCoeff() > 0))
    warnings.add(where, "the transform shrinks the mesh to a point: it covers nothing (is the scale right?)");
}

bool outside_view(const Camera& cam, const Bounds& b) {
  if (!(b.lo.array() <= b.hi.array()).all()) return true;  // no triangles
  // The box's corners in camera space; the view is the frustum z > 0, 0 ≤ u ≤ W, 0 ≤ v ≤ H, i.e.
  // the half-spaces z > 0, fx·x + cx·z ≥ 0, fx·x + (cx − W)·z ≤ 0 and the same in y. The box is
  // outside when all eight corners lie outside one of them (each is linear in the camera frame).
  std::array<Vec3d, 8> c;
  for (int k = 0; k < 8; ++k) {
    const Vec3d p_world(k & 1 ? b.hi.x() : b.lo.x(), k & 2 ? b.hi.y() : b.lo.y(), k & 4 ? b.hi.z() : b.lo.z());
    c[std::size_t(k)] = cam.R_cam_from_world * p_world + cam.t_cam_from_world;
  }
  const std::array<std::function<double(const Vec3d&)>, 5> inside = {
      [](const Vec3d& p) { return p.z(); }, [&](const Vec3d& p) { return cam.fx * p.x() + cam.cx * p.z(); },
      [&](const Vec3d& p) { return -(cam.fx * p.x() + (cam.cx - cam.width) * p.z()); },
      [&](const Vec3d& p) { return cam.fy * p.y() + cam.cy * p.z(); },
      [&](const Vec3d& p) { return -(cam.fy * p.y() + (cam.cy - cam.height) * p.z()); }};
  for (const auto& f : inside)
    if (std::all_of(c.begin(), c.end(), [&](const Vec3d& p) { return f(p) <= 0; })) return true;
  return false;
}

std::vector<NamedPath> scene_input_files(const SceneSpec& spec) {
  std::vector<NamedPath> in = {{spec.path, "the scene file"}, {spec.photo, "the photo"}};
  const EnvironmentSpec& e = spec.environment;
  if (!e.image.empty()) in.push_back({e.image, "the environment"});
  for (int f = 0; f < 6; ++f)
    for (const auto& file : e.shots[std::size_t(f)].files) in.push_back({file, std::string("shot ") + face_name(f)});
  if (!spec.camera.points.empty()) in.push_back({spec.camera.points, "the control points"});
  if (!spec.camera.file.empty())
    in.push_back(
        {spec.camera.file, spec.camera.kind == CameraSpec::Kind::Fspy ? "the fSpy camera" : "the camera file"});
  for (const auto& o : spec.objects) in.push_back({o.mesh, "a mesh (" + o.where + ")"});
  for (const auto& p : spec.local_scene)
    if (p.mesh) in.push_back({p.mesh->mesh, "a local-scene mesh (" + p.mesh->where + ")"});
  return in;
}

std::vector<NamedPath> scene_input_files_with_meshes(const SceneSpec& spec) {
  std::vector<NamedPath> in = scene_input_files(spec);
  std::vector<std::string> meshes;
  for (const auto& o : spec.objects) meshes.push_back(o.mesh);
  for (const auto& p : spec.local_scene)
    if (p.mesh) meshes.push_back(p.mesh->mesh);
  for (const std::string& mesh : meshes)
    for (std::string& file : mesh_dependencies(mesh)) in.push_back({std::move(file), "read by " + mesh});
  return in;
}

std::vector<NamedPath> scene_output_files(const SceneSpec& spec) {
  if (spec.output.image.empty()) return {{spec.output.layers, "the layers"}};
  return {{spec.output.image, "the output image"},
          {spec.output.layers, "the layers"},
          {report_path(spec.output.image), "the report"},
          {checkpoint_path(spec.output.image), "the checkpoint"}};
}

namespace {

// The camera: calibrated from control points (the uncertainty reported at the objects' mean
// position when there are any), or built from the spec.
void load_camera(const SceneSpec& spec, int width, int height, LoadedScene& s) {
  if (spec.camera.kind != CameraSpec::Kind::Points) {
    s.camera = build_camera(spec.camera, width, height, &s.warnings);
    return;
  }
  CalibrationOptions options;
  if (spec.camera.model) options.model = parse_model(*spec.camera.model);
  if (!spec.objects.empty()) {
    Vec3d mean = Vec3d::Zero();
    for (const auto& o : spec.objects)
      mean += o.M_world_from_object.topRightCorner<3, 1>() / double(spec.objects.size());
    options.insertion_world = mean;
  }
  try {
    std::vector<ControlPoint> points;
    for (std::size_t i = 0; i < spec.camera.point_list.size(); ++i)
      points.push_back({spec.camera.point_list[i].uv_px, spec.camera.point_list[i].p_world, fmt::format("#{}", i + 1),
                        fmt::format("points[{}]", i)});
    if (points.empty()) points = read_control_points(spec.camera.points, spec.camera.bottom_left_origin, height);
    s.calibration = calibrate(points, width, height, options);
  } catch (const InputError& e) {
    throw e.with_context(spec.camera.where + ".points");
  }
  s.camera = s.calibration->camera;
  for (const auto& w : s.calibration->warnings.items) s.warnings.add(spec.camera.where, w);
}

// The calibration's uncertainty at each object's bounding-box corners (object_uncertainty.h),
// a warning for objects outside the clicks' span, with where to click next.
void objects_uncertainty(const SceneSpec& spec, const std::vector<Mesh>& meshes, LoadedScene& s) {
  if (!s.calibration || meshes.empty()) return;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const Bounds b = mesh_bounds(meshes[i]);
    if (!b.lo.allFinite() || !b.hi.allFinite()) continue;
    const std::string name =
        i < spec.objects.size()
            ? fmt::format("objects[{}] ({})", i, std::filesystem::path(spec.objects[i].mesh).filename().string())
            : meshes[i].source;
    s.object_uncertainty.push_back(
        object_uncertainty(*s.calibration, name, box_corners(b.lo.cast<double>(), b.hi.cast<double>())));
  }
  s.click_hint = suggest_next_click(*s.calibration, s.object_uncertainty);
  const std::string warning = outside_clicks_warning(s.object_uncertainty, s.click_hint);
  if (!warning.empty()) s.warnings.add(spec.camera.where, warning);
}

// A mesh read and placed by its transform; errors carry the spec's JSON location.
Mesh load_placed_mesh(const ObjectSpec& obj, Warnings& warnings) {
  Mesh mesh;
  try {
    mesh = load_mesh(obj.mesh, warnings);
  } catch (const InputError& e) {
    throw e.with_context(obj.where + ".mesh");
  }
  try {
    transform_mesh(mesh, obj.M_world_from_object);
  } catch (const InputError& e) {
    throw e.with_context(obj.where);
  }
  warn_if_collapsed(mesh, obj.where, warnings);
  return mesh;
}

// The files the meshes named (MTL, textures) are inputs too.
void check_mesh_files(const std::vector<Mesh>& meshes, const SceneSpec& spec) {
  std::vector<NamedPath> mesh_files;
  for (const Mesh& m : meshes)
    for (const auto& f : m.files) mesh_files.push_back({f, "read by " + m.source});
  check_outputs(mesh_files, scene_output_files(spec));
}

}  // namespace

// Every corner of a reference polygon lies within the photo.
void check_references(const SceneSpec& spec, int width, int height) {
  for (const ReferenceSpec& r : spec.references)
    for (std::size_t i = 0; i < r.polygon_px.size(); ++i) {
      const Vec2d& p = r.polygon_px[i];
      if (!(p.x() >= 0 && p.y() >= 0 && p.x() <= width && p.y() <= height))
        throw InputError(fmt::format("{}.polygon_px[{}]", r.where, i),
                         fmt::format("({}, {}) lies outside the photo ({} x {} pixels)", p.x(), p.y(), width, height));
    }
}

namespace {

ImageFile read_photo(const SceneSpec& spec) {
  try {
    return read_image_file(spec.photo);
  } catch (const InputError& e) {
    throw e.with_context(spec.photo_where);
  }
}

// The room: the photo, the environment (the photo linearized with its response), the camera, the
// room box and the clipped light recovered against the photo.
void load_room(const SceneSpec& spec, LoadedScene& s, const std::atomic<bool>* stop) {
  s.photo = read_photo(spec);
  throw_if_stopped(stop);
  // The camera first (it anchors handheld shots without a room box to the photo), then the
  // environment: brackets may recover the camera response that linearizes the photo.
  load_camera(spec, s.photo.stored.width, s.photo.stored.height, s);
  throw_if_stopped(stop);
  s.environment = load_environment(spec.environment, s.warnings, &s.environment_info, &s.photo, &s.camera);
  throw_if_stopped(stop);
  std::size_t clamped = 0;
  s.photo_linear = linearize_photo(s.photo, s.environment_info, &clamped);
  if (clamped > 0) s.warnings.add(spec.photo, fmt::format("{} negative or non-finite values clamped to 0", clamped));
  check_references(spec, s.photo.stored.width, s.photo.stored.height);
  if (const auto& box = spec.environment.room_box) {
    RoomBox room{box->min.cast<float>(), box->max.cast<float>(), box->capture.cast<float>(), {}, std::nullopt};
    for (const auto& o : box->openings) room.openings.push_back({o.axis, o.min.cast<float>(), o.max.cast<float>()});
    s.room = room;
  }
  throw_if_stopped(stop);
  match_white_balance(s);
  fill_uncovered_from_photo(s);
  recover_clipped_light(s, stop);
  s.room_cache = std::make_shared<RoomCache>(s.environment, s.room);
}

// The room of `from`, loaded already (a batch's entries share it).
void copy_room(const LoadedScene& from, LoadedScene& s) {
  s.photo = from.photo, s.photo_linear = from.photo_linear, s.camera = from.camera, s.calibration = from.calibration;
  s.environment = from.environment, s.environment_info = from.environment_info, s.room = from.room;
  s.inverse_lighting = from.inverse_lighting, s.unseen_outside = from.unseen_outside, s.room_cache = from.room_cache,
  s.white_balance = from.white_balance, s.photo_fill = from.photo_fill;
  s.warnings.items.insert(s.warnings.items.end(), from.room_warnings.items.begin(), from.room_warnings.items.end());
}

// The principled model (glTF) is the path integrator's: the others say which materials they shade by
// base colour alone. (OBJ's Ks, which the legacy renderer never drew either, goes unremarked.)
void warn_base_colour_only(const std::vector<Mesh>& meshes, const std::string& integrator, Warnings& w) {
  if (integrator == "path") return;
  std::string names;
  for (const Mesh& m : meshes)
    for (const Material& mat : m.materials)
      if (mat.principled && names.find("'" + mat.name + "'") == std::string::npos)
        names += (names.empty() ? "'" : ", '") + mat.name + "'";
  if (!names.empty())
    w.add("render.integrator",
          "the " + integrator +
              " integrator shades the objects by their base colour only; metallic, roughness, "
              "specular, clear coat, sheen, glass and emission are the path integrator's (materials " +
              names + ")");
}

// The objects (from the spec, then from memory) and the local scene's meshes.
void load_objects(const SceneSpec& spec, std::vector<Mesh> memory_objects, LoadedScene& s,
                  const std::atomic<bool>* stop) {
  std::vector<Mesh> meshes;
  for (const ObjectSpec& obj : spec.objects) {
    throw_if_stopped(stop);
    meshes.push_back(load_placed_mesh(obj, s.warnings));
    if (outside_view(s.camera, mesh_bounds(meshes.back())))
      s.warnings.add(
          obj.where,
          "the object lies entirely outside the camera's view (it covers no pixel): check translate and the camera");
  }
  check_mesh_files(meshes, spec);
  for (Mesh& m : memory_objects) {
    warn_if_collapsed(m, m.source, s.warnings);
    if (outside_view(s.camera, mesh_bounds(m)))
      s.warnings.add(m.source,
                     "the object lies entirely outside the camera's view (it covers no pixel): check its transform and "
                     "the camera");
    meshes.push_back(std::move(m));
  }
  throw_if_stopped(stop);
  warn_base_colour_only(meshes, spec.render.integrator, s.warnings);
  objects_uncertainty(spec, meshes, s);
  s.objects = std::make_unique<EmbreeScene>(std::move(meshes));
  std::vector<Mesh> catcher_meshes;
  for (const PlaneSpec& p : spec.local_scene) {
    if (!p.mesh) continue;
    throw_if_stopped(stop);
    catcher_meshes.push_back(load_placed_mesh(*p.mesh, s.warnings));
  }
  check_mesh_files(catcher_meshes, spec);
  s.catcher_meshes = std::make_unique<EmbreeScene>(std::move(catcher_meshes));
}

}  // namespace

PhotoAndCamera load_photo_and_camera(const SceneSpec& spec, Warnings& warnings) {
  LoadedScene s;
  s.photo = read_photo(spec);
  load_camera(spec, s.photo.stored.width, s.photo.stored.height, s);
  warnings.items.insert(warnings.items.end(), s.warnings.items.begin(), s.warnings.items.end());
  return {std::move(s.photo), s.camera};
}

LoadedScene load_scene(const SceneSpec& spec, std::vector<Mesh> memory_objects, const LoadedScene* room,
                       const std::atomic<bool>* stop) {
  const auto start = std::chrono::steady_clock::now();
  // Before any work: no output may replace an input or another output.
  check_outputs(scene_input_files(spec), scene_output_files(spec));
  LoadedScene s;
  s.spec = spec;
  s.warnings = spec.warnings;
  // The integrator reads its parameters before anything is loaded: a typo costs nothing.
  s.integrator = resolve_integrator(spec.render.integrator, spec.render.block, s.warnings);
  warn_ineffective_settings(spec, s.integrator, s.warnings);
  if (s.integrator.params.value("irradiance", "") == "volume" && !spec.environment.room_box)
    throw InputError(spec.render.block.file + ":" + spec.render.block.path,
                     "the volume irradiance mode needs environment.room_box");
  if (room) {
    copy_room(*room, s);
  } else {
    const std::size_t before = s.warnings.items.size();
    load_room(spec, s, stop);
    s.room_warnings.items.assign(s.warnings.items.begin() + long(before), s.warnings.items.end());
  }
  load_objects(spec, std::move(memory_objects), s, stop);
  s.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

RenderResult render_scene(const LoadedScene& scene, const ProgressFn& progress, const RenderControl& control) {
  RenderInputs inputs;
  inputs.objects = scene.objects.get();
  inputs.environment = &scene.environment;
  inputs.photo_linear = &scene.photo_linear;
  inputs.room = scene.room;
  inputs.camera = &scene.camera;
  inputs.room_cache = scene.room_cache;
  if (control.stop_at_once) inputs.stop = control.stop;  // the studio's stop: also during the preparation
  // Everything before the sample loop is preparation: the catcher's irradiance included.
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<IrradianceField> catcher_irradiance;
  // The catchers' irradiance only for an integrator that catches (realtime and irradiance ignore
  // the local scene: its exact irradiance was most of `realtime`'s preparation).
  const std::vector<PlaneSpec> no_planes;
  for (const PlaneSpec& p : scene.integrator.entry->uses.local_scene ? scene.spec.local_scene : no_planes) {
    if (p.mesh) {
      inputs.catcher_mesh_info.push_back({p.albedo_from_photo, p.albedo});
      continue;
    }
    CatcherPlane c;
    c.point = p.point.cast<float>();
    c.normal = p.normal.normalized().cast<float>();
    // The side the camera sees.
    if (c.normal.dot(scene.camera.eye_world().cast<float>() - c.point) < 0) c.normal = -c.normal;
    c.albedo_from_photo = p.albedo_from_photo;
    c.albedo = p.albedo;
    c.irradiance = irradiance_reference(scene.environment, c.normal.cast<double>());
    inputs.planes.push_back(c);
  }
  if (!inputs.catcher_mesh_info.empty()) {
    catcher_irradiance = make_irradiance(IrradianceMode::kExact, scene.environment, 32, inputs.stop);
    inputs.catcher_meshes = scene.catcher_meshes.get();
    inputs.catcher_irradiance = catcher_irradiance.get();
  }
  auto integrator = scene.integrator.entry->create(inputs, scene.integrator.params);
  const double prepare_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const RenderSettings settings{scene.spec.render.spp, scene.spec.render.seed, control.stop,
                                control.sample_begin,  control.sample_end,     scene.spec.render.noise_target,
                                control.stop_at_once};
  return finish_render(scene, render(scene.camera, *integrator, settings, progress, control.state), prepare_seconds);
}

namespace {

// Whether some pixel has two samples or more, the least its variance is estimated from.
bool has_sample_spread(const RenderLayers& layers) {
  return std::any_of(layers.samples.data.begin(), layers.samples.data.end(), [](float n) { return n >= 2; });
}

}  // namespace

bool denoises(const LoadedScene& scene, std::optional<bool> denoise) {
  return denoise.value_or(scene.spec.denoise) && scene.integrator.entry->uses.monte_carlo;
}

RenderResult finish_render(const LoadedScene& scene, RenderLayers layers, double prepare_seconds,
                           std::optional<bool> denoise) {
  RenderResult r;
  r.prepare_seconds = prepare_seconds;
  r.layers = std::move(layers);
  r.composite_linear = composite(scene.photo_linear, r.layers, scene.spec.composite);
  // The pixels that are not the photo's own: those the render touched, and with the denoiser
  // those it estimated (output/denoise.h).
  Image changed = touched_mask(r.layers);
  r.denoise_asked = denoises(scene, denoise);
  if (r.denoise_asked && has_sample_spread(r.layers)) {
    const auto start = std::chrono::steady_clock::now();
    const Image variance = composite_variance(scene.photo_linear, r.layers, scene.spec.composite);
    Denoised d = denoise_composite(scene.photo_linear, r.composite_linear, variance, r.layers);
    r.composite_linear = std::move(d.composite);
    changed = std::move(d.estimated);
    r.denoise_block = d.block;
    r.denoise_pixels_alone = d.pixels_fitted_alone;
    r.denoised = true;
    r.denoise_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  r.composite_encoded = encode_composite(r.composite_linear, changed, scene.photo,
                                         scene.environment_info.response ? &*scene.environment_info.response : nullptr);
  return r;
}

namespace {

nlohmann::json denoise_report(const RenderResult& r) {
  if (r.denoised)
    return {
        {"seconds", r.denoise_seconds}, {"block", r.denoise_block}, {"pixels_fitted_alone", r.denoise_pixels_alone}};
  if (r.denoise_asked)
    return {
        {"skipped", "no pixel has two samples, the least its noise is estimated from: the composite is as rendered"}};
  return nullptr;
}

// Adaptive sampling's outcome: the target, the mean spp, and how many pixels took each count.
nlohmann::json adaptive_report(double noise_target, const RenderLayers& layers) {
  if (!(noise_target > 0)) return nullptr;
  std::map<int, long> histogram;
  for (float n : layers.samples.data) ++histogram[int(n)];
  nlohmann::json bins = nlohmann::json::array();
  for (const auto& [spp, pixels] : histogram) bins.push_back({{"spp", spp}, {"pixels", pixels}});
  return {{"noise_target", noise_target}, {"mean_spp", mean_spp(layers)}, {"spp_histogram", bins}};
}

}  // namespace

std::string report_path(const std::string& image_path) { return image_path + ".report.json"; }

nlohmann::json render_report(const LoadedScene& s, const RenderResult& r, const OutputSpec* output) {
  using nlohmann::json;
  SceneSpec tonemap_spec;
  tonemap_spec.output = output ? *output : s.spec.output;
  const auto& info = s.environment_info;
  json shots = json::array();
  if (s.spec.environment.from_shots())
    for (int f = 0; f < 6; ++f) shots.push_back(shot_report(s.spec.environment, info, f));
  json calibration = nullptr;
  if (s.calibration)
    calibration = {{"model", model_name(s.calibration->model)},
                   {"rms_px", s.calibration->rms_px},
                   {"inliers", s.calibration->inliers},
                   {"insertion_sigma_px", s.calibration->insertion_sigma_px},
                   {"at_objects", object_uncertainty_json(s.object_uncertainty, s.click_hint)}};
  return json{
      {"scene", s.spec.path},
      {"image", {{"width", s.camera.width}, {"height", s.camera.height}}},
      {"seconds", {{"load", s.load_seconds}, {"prepare", r.prepare_seconds}, {"render", r.layers.seconds}}},
      {"calibration", calibration},
      {"environment",
       {{"face_size", s.environment.size()},
        {"exposure", info.exposure_source},
        {"exposure_factor", info.exposure_factor},
        {"response_from_brackets", info.response.has_value()},
        {"clamped_values", info.clamped_values},
        {"shots", shots},
        {"panorama", info.panorama ? json{{"coverage_percent", 100 * info.panorama_coverage},
                                          {"clipped_percent", 100 * info.panorama_clipped},
                                          {"yaw_deg", s.spec.environment.yaw_deg}}
                                   : json(nullptr)},
        {"white_balance", white_balance_report(s)},
        {"photo_fill", photo_fill_report(s)},
        {"light", light_report(s)}}},
      {"render",
       {{"integrator", s.spec.render.integrator},
        {"parameters", s.integrator.params},
        {"irradiance", s.integrator.params.value("irradiance", json(nullptr))},
        {"spp", r.layers.spp_done},  // the samples taken: fewer than planned when interrupted
        {"spp_planned", s.spec.render.spp},
        {"samples", {r.layers.sample_begin, r.layers.sample_begin + r.layers.spp_done}},  // indices [A, B) of the plan
        {"interrupted", r.layers.interrupted},
        {"max_depth", s.integrator.params.value("max_depth", json(nullptr))},
        {"seed", s.spec.render.seed},
        {"noise_relative", r.layers.mean_relative_noise},
        {"adaptive", adaptive_report(s.spec.render.noise_target, r.layers)},
        {"nonfinite_samples", r.layers.nonfinite_samples}}},
      {"composite", name_of(kCompositeModes, s.spec.composite)},
      {"denoise", denoise_report(r)},
      {"tonemap", effective_tonemap(tonemap_spec)},
      {"warnings", s.warnings.items},
  };
}

}  // namespace insitu
