// The insitu command line: a thin shell over the library (DESIGN.md "Layout").
//
//   insitu render SCENE [-o OUT] [--spp N] [--integrator NAME] [--seed N]
//   insitu calibrate --points P (--image PHOTO | --size W H) [--model M] [--origin O] [--at X Y Z]
//                    [-o camera.json] [--vc OUT.vc]
//   insitu --help | --version
//
// Bad input: one line `insitu: error: <where>: <what>` on stderr, exit code 2, nothing written.
// Internal failure: exit code 1.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fmt/format.h>

#include "calibration.h"
#include "integrators/integrator.h"
#include "pipeline.h"
#include "progress.h"
#include "text_file.h"
#include "view_correlation.h"

namespace {

using namespace insitu;

struct RenderArgs {
  std::string scene;
  std::string output;
  int spp = 0;
  long seed = -1;
  std::string integrator;
};

void print_warnings(const Warnings& w) {
  for (const auto& item : w.items) std::fprintf(stderr, "insitu: warning: %s\n", item.c_str());
}

int run_render(const RenderArgs& a) {
  SceneSpec spec = parse_scene_file(a.scene);
  if (!a.output.empty()) {
    std::string ext = std::filesystem::path(a.output).extension().string();
    for (auto& c : ext) c = char(std::tolower(c));
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".exr" && ext != ".tif" && ext != ".tiff")
      throw InputError("-o " + a.output, "unsupported extension '" + ext + "' (use .png, .jpg, .exr, .tif)");
    spec.output.image = a.output;
  }
  if (a.spp > 0) spec.render.spp = a.spp;
  if (a.seed >= 0) spec.render.seed = std::uint64_t(a.seed);
  if (!a.integrator.empty()) {
    if (!is_integrator(a.integrator)) make_integrator(a.integrator, {});  // throws, naming the known ones
    spec.render.integrator = a.integrator;
  }
  LoadedScene scene = load_scene(spec);
  print_warnings(scene.warnings);
  RenderResult result;
  {
    Progress progress("render");
    result = render_scene(scene, [&](double f) { progress.update(f); });
  }
  write_outputs(scene, result);
  std::printf("%s\n", spec.output.image.c_str());
  if (!spec.output.layers.empty()) std::printf("%s\n", spec.output.layers.c_str());
  std::fprintf(stderr, "insitu: %s, %dx%d, %d spp, integrator %s: load %.2f s, render %.2f s\n",
               spec.path.c_str(), scene.camera.width, scene.camera.height, spec.render.spp,
               spec.render.integrator.c_str(), scene.load_seconds, result.layers.seconds);
  if (result.layers.nonfinite_samples > 0)
    std::fprintf(stderr, "insitu: warning: %zu non-finite samples zeroed\n", result.layers.nonfinite_samples);
  return 0;
}

struct CalibrateArgs {
  std::string points;
  std::string image;
  std::vector<int> size;
  std::string model = "auto";
  std::string origin = "top-left";
  std::vector<double> at;
  std::string output;
  std::string vc;
};

int run_calibrate(const CalibrateArgs& a) {
  int width = 0, height = 0;
  if (!a.image.empty()) {
    std::tie(width, height) = read_image_size(a.image);
  } else {
    width = a.size[0];
    height = a.size[1];
  }
  CalibrationOptions options;
  if (a.model != "auto") options.model = parse_model(a.model);
  if (!a.at.empty()) options.insertion_world = Vec3d(a.at[0], a.at[1], a.at[2]);
  const auto points = read_control_points(a.points, a.origin == "bottom-left", height);
  CalibrationResult r;
  try {
    r = calibrate(points, width, height, options);
  } catch (const InputError& e) {
    throw e.with_context(a.points);
  }
  std::printf("%s", calibration_report(r).c_str());
  if (!a.output.empty()) {
    write_text_file(a.output, calibration_to_json(r).dump(2) + "\n");
    std::printf("wrote %s\n", a.output.c_str());
  }
  if (!a.vc.empty()) {
    std::vector<ControlPoint> inliers;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (!r.points[i].outlier) inliers.push_back(points[i]);
    write_view_correlation(a.vc, view_correlation_from_camera(r.camera, inliers));
    std::printf("wrote %s\n", a.vc.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"insitu: physically based insertion of 3D furniture into a photograph of a room"};
  app.set_version_flag("--version", std::string("insitu ") + INSITU_VERSION);
  app.require_subcommand(1);

  RenderArgs render_args;
  CLI::App* render = app.add_subcommand("render", "render a scene file to a composite image");
  render->add_option("scene", render_args.scene, "the scene file (JSON)")->required();
  render->add_option("-o,--output", render_args.output, "the composite image (overrides output.image)");
  render->add_option("--spp", render_args.spp, "samples per pixel")->check(CLI::Range(1, 1 << 20));
  render->add_option("--seed", render_args.seed, "random seed")->check(CLI::Range(0L, 1L << 62));
  std::string integrators_help = "integrator:";
  for (const auto& e : integrator_registry()) integrators_help += fmt::format(" {} ({})", e.name, e.summary);
  render->add_option("--integrator", render_args.integrator, integrators_help);

  CalibrateArgs cal;
  CLI::App* calibrate_cmd = app.add_subcommand("calibrate", "recover the camera from 2D-3D control points");
  calibrate_cmd->add_option("--points", cal.points, "control points: .json, .csv or a View Correlation .vc file")->required();
  auto* image_opt = calibrate_cmd->add_option("--image", cal.image, "the photo (for its size)");
  auto* size_opt = calibrate_cmd->add_option("--size", cal.size, "the photo's size in pixels")->expected(2)->check(CLI::PositiveNumber);
  image_opt->excludes(size_opt);
  calibrate_cmd->add_option("--model", cal.model, "camera model: auto, f, f+c, f+c+a")
      ->check(CLI::IsMember({"auto", "f", "f+c", "f+c+a"}));
  calibrate_cmd->add_option("--origin", cal.origin, "pixel origin of the points: top-left or bottom-left")
      ->check(CLI::IsMember({"top-left", "bottom-left"}));
  calibrate_cmd->add_option("--at", cal.at, "world point (m) where the uncertainty in pixels is reported")->expected(3);
  calibrate_cmd->add_option("-o,--output", cal.output, "write camera.json");
  calibrate_cmd->add_option("--vc", cal.vc, "also write the View Correlation parameter set");

  try {
    app.parse(argc, argv);
    if (calibrate_cmd->parsed() && cal.image.empty() && cal.size.empty())
      throw CLI::RequiredError("--image or --size");
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string msg = e.what();
    if (auto nl = msg.find('\n'); nl != std::string::npos) msg.resize(nl);
    std::fprintf(stderr, "insitu: error: %s (see insitu --help)\n", msg.c_str());
    return 2;
  }
  try {
    if (render->parsed()) return run_render(render_args);
    if (calibrate_cmd->parsed()) return run_calibrate(cal);
  } catch (const InputError& e) {
    std::string msg = e.what();
    for (auto& c : msg)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "insitu: error: %s\n", msg.c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "insitu: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
