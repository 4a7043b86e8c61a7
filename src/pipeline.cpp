#include "pipeline.h"

#include <chrono>
#include <filesystem>
#include <fmt/format.h>

#include "composite.h"
#include "integrators/integrator.h"
#include "text_file.h"
#include "irradiance.h"

namespace insitu {

LoadedScene load_scene(const SceneSpec& spec) {
  const auto start = std::chrono::steady_clock::now();
  LoadedScene s;
  s.spec = spec;
  try {
    s.photo = read_image_file(spec.photo);
  } catch (const InputError& e) {
    throw e.with_context(spec.photo_where);
  }
  // The environment first: brackets may recover the camera response that linearizes the photo.
  s.environment = load_environment(spec.environment, s.warnings, &s.environment_info, &s.photo);
  std::size_t clamped = 0;
  s.photo_linear = linearize_photo(s.photo, s.environment_info, &clamped);
  if (clamped > 0) s.warnings.add(spec.photo, fmt::format("{} negative or non-finite values clamped to 0", clamped));
  const int width = s.photo.stored.width, height = s.photo.stored.height;
  if (spec.camera.kind == CameraSpec::Kind::Points) {
    // Calibrate; the uncertainty is reported at the objects' mean position when there are any.
    CalibrationOptions options;
    if (spec.camera.model) options.model = parse_model(*spec.camera.model);
    if (!spec.objects.empty()) {
      Vec3d mean = Vec3d::Zero();
      for (const auto& o : spec.objects) mean += o.M_world_from_object.topRightCorner<3, 1>() / double(spec.objects.size());
      options.insertion_world = mean;
    }
    try {
      const auto points = read_control_points(spec.camera.points, spec.camera.bottom_left_origin, height);
      s.calibration = calibrate(points, width, height, options);
    } catch (const InputError& e) {
      throw e.with_context(spec.camera.where + ".points");
    }
    s.camera = s.calibration->camera;
    for (const auto& w : s.calibration->warnings) s.warnings.add(spec.camera.where, w);
  } else {
    s.camera = build_camera(spec.camera, width, height);
  }

  std::vector<Mesh> meshes;
  for (const ObjectSpec& obj : spec.objects) {
    Mesh mesh;
    try {
      mesh = load_obj(obj.mesh, s.warnings);
    } catch (const InputError& e) {
      throw e.with_context(obj.where + ".mesh");
    }
    transform_mesh(mesh, obj.M_world_from_object);
    meshes.push_back(std::move(mesh));
  }
  if (!spec.local_scene.empty() && spec.render.integrator != "path")
    s.warnings.add(spec.path, "local_scene is used only by the path integrator (" + spec.render.integrator +
                                  " draws no shadows on it)");
  s.objects = std::make_unique<EmbreeScene>(std::move(meshes));
  std::vector<Mesh> catcher_meshes;
  for (std::size_t i = 0; i < spec.local_scene.size(); ++i) {
    const auto& m = spec.local_scene[i].mesh;
    if (!m) continue;
    Mesh mesh;
    try {
      mesh = load_obj(m->mesh, s.warnings);
    } catch (const InputError& e) {
      throw e.with_context(m->where + ".mesh");
    }
    transform_mesh(mesh, m->M_world_from_object);
    catcher_meshes.push_back(std::move(mesh));
  }
  s.catcher_meshes = std::make_unique<EmbreeScene>(std::move(catcher_meshes));
  s.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

RenderResult render_scene(const LoadedScene& scene, const ProgressFn& progress) {
  RenderInputs inputs;
  inputs.objects = scene.objects.get();
  inputs.environment = &scene.environment;
  inputs.irradiance_mode = scene.spec.render.irradiance;
  inputs.photo_linear = &scene.photo_linear;
  if (const auto& box = scene.spec.environment.room_box) {
    inputs.room_box = true;
    inputs.box_min = box->min.cast<float>();
    inputs.box_max = box->max.cast<float>();
    inputs.capture = box->capture.cast<float>();
  }
  inputs.camera = &scene.camera;
  std::unique_ptr<IrradianceField> catcher_irradiance;
  for (const PlaneSpec& p : scene.spec.local_scene) {
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
    catcher_irradiance = make_irradiance(IrradianceMode::kExact, scene.environment);
    inputs.catcher_meshes = scene.catcher_meshes.get();
    inputs.catcher_irradiance = catcher_irradiance.get();
  }
  inputs.max_depth = scene.spec.render.max_depth;
  const auto start = std::chrono::steady_clock::now();
  auto integrator = make_integrator(scene.spec.render.integrator, inputs);
  RenderResult r;
  r.prepare_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.layers = render(scene.camera, *integrator, scene.spec.render, progress);
  r.composite_linear = composite(scene.photo_linear, r.layers, scene.spec.composite);
  r.composite_encoded = encode_composite(r.composite_linear, touched_mask(r.layers), scene.photo,
                                         scene.environment_info.response ? &*scene.environment_info.response : nullptr);
  return r;
}

std::string report_path(const std::string& image_path) {
  const std::filesystem::path p(image_path);
  return (p.parent_path() / (p.stem().string() + ".report.json")).string();
}

nlohmann::json render_report(const LoadedScene& s, const RenderResult& r) {
  using nlohmann::json;
  const auto& info = s.environment_info;
  json shots = json::array();
  if (s.spec.environment.from_shots())
    for (int f = 0; f < 6; ++f)
      shots.push_back({{"face", face_name(f)},
                       {"files", s.spec.environment.shots[std::size_t(f)].files},
                       {"coverage_percent", 100 * info.coverage[std::size_t(f)]},
                       {"clipped_percent", 100 * info.clipped[std::size_t(f)]}});
  json calibration = nullptr;
  if (s.calibration)
    calibration = {{"model", model_name(s.calibration->model)},
                   {"rms_px", s.calibration->rms_px},
                   {"inliers", s.calibration->inliers},
                   {"insertion_sigma_px", s.calibration->insertion_sigma_px}};
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
        {"shots", shots}}},
      {"render",
       {{"integrator", s.spec.render.integrator},
        {"irradiance", irradiance_mode_name(s.spec.render.irradiance)},
        {"spp", s.spec.render.spp},
        {"max_depth", s.spec.render.max_depth},
        {"seed", s.spec.render.seed},
        {"noise_relative", r.layers.mean_relative_noise},
        {"nonfinite_samples", r.layers.nonfinite_samples}}},
      {"composite", s.spec.composite == CompositeMode::kRatio ? "ratio" : "additive"},
      {"tonemap", tonemap_name(s.spec.output.tonemap.op)},
      {"warnings", s.warnings.items},
  };
}

void write_outputs(const LoadedScene& scene, const RenderResult& r) {
  const std::string& image = scene.spec.output.image;
  std::string ext = std::filesystem::path(image).extension().string();
  for (auto& c : ext) c = char(std::tolower(c));
  const bool linear_out = ext == ".exr" || ext == ".tif" || ext == ".tiff";
  const ToneMapSettings& tm = scene.spec.output.tonemap;
  write_image(image, linear_out ? r.composite_linear
                                : tm.op == ToneMap::kPhoto ? r.composite_encoded : tonemap(r.composite_linear, tm));
  write_text_file(report_path(image), render_report(scene, r).dump(2) + "\n");
  if (!scene.spec.output.layers.empty()) {
    const Image &c = r.composite_linear, &o = r.layers.objects, &a = r.layers.alpha;
    const Image &w = r.layers.with_objects, &n = r.layers.without_objects;
    const Image ratio = shadow_ratio(r.layers);
    write_exr_channels(scene.spec.output.layers, c.width, c.height,
                       {{"R", &c, 0}, {"G", &c, 1}, {"B", &c, 2},
                        {"objects.R", &o, 0}, {"objects.G", &o, 1}, {"objects.B", &o, 2}, {"objects.A", &a, 0},
                        {"with.R", &w, 0}, {"with.G", &w, 1}, {"with.B", &w, 2},
                        {"without.R", &n, 0}, {"without.G", &n, 1}, {"without.B", &n, 2},
                        {"shadow_ratio.R", &ratio, 0}, {"shadow_ratio.G", &ratio, 1}, {"shadow_ratio.B", &ratio, 2},
                        {"normal.X", &r.layers.normal, 0}, {"normal.Y", &r.layers.normal, 1}, {"normal.Z", &r.layers.normal, 2},
                        {"albedo.R", &r.layers.albedo, 0}, {"albedo.G", &r.layers.albedo, 1}, {"albedo.B", &r.layers.albedo, 2},
                        {"depth.Z", &r.layers.depth, 0}, {"samples.Y", &r.layers.samples, 0}, {"variance.Y", &r.layers.variance, 0},
                        {"photo.R", &scene.photo_linear, 0}, {"photo.G", &scene.photo_linear, 1},
                        {"photo.B", &scene.photo_linear, 2}});
  }
}

}  // namespace insitu
