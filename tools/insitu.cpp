// The insitu command line: a thin shell over the library (DESIGN.md "Layout").
//
//   insitu render SCENE [-o OUT] [--spp N] [--integrator NAME] [--seed N]
//   insitu --help | --version
//
// Bad input: one line `insitu: error: <where>: <what>` on stderr, exit code 2, nothing written.
// Internal failure: exit code 1.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <fmt/format.h>

#include "integrators/integrator.h"
#include "pipeline.h"
#include "progress.h"

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

  try {
    app.parse(argc, argv);
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
