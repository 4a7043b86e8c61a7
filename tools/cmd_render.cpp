// insitu render SCENE [-o OUT] [--layers PATH|none] [--spp N] [--integrator NAME] [--irradiance MODE]
//                     [--seed N] [--tonemap OP] [--key K] [--resume]
//
// SIGINT or SIGTERM finishes the pass under way, writes the partial image, layers and report (its
// spp the samples taken), and a checkpoint beside the image (OUT.checkpoint, render/checkpoint.h),
// and exits 130; --resume continues from the checkpoint to the image an uninterrupted render gives,
// bit for bit. A second signal ends the process at once (no half-written file, the checkpoint as
// it was).
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <memory>

#include "core/output_paths.h"
#include "core/temp_files.h"
#include "render/checkpoint.h"
#include "commands.h"
#include "integrators/registry.h"
#include "scene/pipeline.h"
#include "progress.h"

namespace insitu {

void print_warnings(const Warnings& w) {
  for (const auto& item : w.items) std::fprintf(stderr, "insitu: warning: %s\n", item.c_str());
}

namespace {

struct RenderArgs {
  std::string scene, output, layers, integrator, irradiance, tonemap;
  double key = 0;
  int spp = 0;
  long seed = -1;
  bool resume = false;
};

// The render, stoppable by SIGINT/SIGTERM and resumable from `state`.
RenderResult render_with_progress(const LoadedScene& scene, RenderState& state) {
  Progress progress("render");
  std::string detail;
  arm_graceful_stop(true);
  RenderResult result = render_scene(scene, [&](const RenderProgress& p) {
    const bool pass_end = p.noise >= 0;
    if (pass_end) detail = fmt::format("{}/{} spp, noise {:.1f}%", p.spp_done, scene.spec.render.spp, 100 * p.noise);
    progress.update(p.fraction, detail, pass_end);
  }, {&graceful_stop_flag(), &state});
  arm_graceful_stop(false);
  return result;
}

// The scene file with the command line's overrides.
SceneSpec render_spec(const RenderArgs& a) {
  SceneSpec spec = parse_scene_file(a.scene);
  if (!a.output.empty()) {
    const std::string ext = lower_extension(a.output);
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".exr" && ext != ".tif" && ext != ".tiff")
      throw InputError("-o " + a.output, "unsupported extension '" + ext + "' (use .png, .jpg, .exr, .tif)");
    spec.output.image = a.output;
    // A quick `-o test.png` must not overwrite the final render's layers and report.
    spec.output.layers = layers_path_for(a.output);
  }
  if (!a.layers.empty()) {
    if (a.layers == "none") {
      spec.output.layers.clear();
    } else {
      if (lower_extension(a.layers) != ".exr") throw InputError("--layers " + a.layers, "the layers are a multi-layer EXR: use .exr, or none");
      spec.output.layers = a.layers;
    }
  }
  if (a.spp > 0) spec.render.spp = a.spp;
  if (a.seed >= 0) spec.render.seed = std::uint64_t(a.seed);
  if (!a.integrator.empty()) {
    if (!find_integrator(a.integrator)) throw InputError("--integrator", unknown_integrator_message(a.integrator));
    spec.render.integrator = a.integrator;
  }
  if (!a.irradiance.empty()) {
    spec.render.block.value["irradiance"] = a.irradiance;
  }
  if (!a.tonemap.empty()) {
    spec.output.tonemap.op = *parse_tonemap(a.tonemap);
    spec.given.insert("output.tonemap");
  }
  if (a.key > 0) {
    spec.output.tonemap.key = a.key;
    spec.given.insert("output.tonemap.key");
  }
  return spec;
}

int run_render(const RenderArgs& a) {
  const SceneSpec spec = render_spec(a);
  LoadedScene scene = load_scene(spec);
  print_warnings(scene.warnings);
  const std::string checkpoint = checkpoint_path(spec.output.image);
  const std::uint64_t fingerprint = render_fingerprint(scene);
  RenderState state;
  if (a.resume) state = read_checkpoint(checkpoint, fingerprint);
  const RenderResult result = render_with_progress(scene, state);
  write_outputs(scene, result);
  if (result.layers.interrupted) {
    write_checkpoint(checkpoint, state, fingerprint);
    std::fprintf(stderr, "insitu: interrupted after %d of %d spp: wrote the partial image and %s (continue with --resume)\n",
                 result.layers.spp_done, spec.render.spp, checkpoint.c_str());
    return 130;
  }
  std::error_code ignored;
  std::filesystem::remove(checkpoint, ignored);  // used up: the image is complete
  std::printf("%s\n", spec.output.image.c_str());
  if (!spec.output.layers.empty()) std::printf("%s\n", spec.output.layers.c_str());
  std::fprintf(stderr, "insitu: %s, %dx%d, %d spp, integrator %s: load %.2f s, prepare %.2f s, render %.2f s\n",
               spec.path.c_str(), scene.camera.width, scene.camera.height, spec.render.spp,
               spec.render.integrator.c_str(), scene.load_seconds, result.prepare_seconds, result.layers.seconds);
  if (result.layers.mean_relative_noise > 0)
    std::fprintf(stderr, "insitu: noise estimate: %.2f%% relative standard error where the render changed the photo\n",
                 100 * result.layers.mean_relative_noise);
  if (result.layers.nonfinite_samples > 0)
    std::fprintf(stderr, "insitu: warning: %zu non-finite samples zeroed\n", result.layers.nonfinite_samples);
  return 0;
}

}  // namespace

Command add_render_command(CLI::App& app) {
  auto a = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "render a scene file to a composite image");
  cmd->add_option("scene", a->scene, "the scene file (JSON)")->required();
  cmd->add_option("-o,--output", a->output,
                  "the composite image (overrides output.image; .png, .jpg, .exr, .tif); the layers and the report "
                  "follow it: OUT_STEM.layers.exr, OUT.report.json");
  cmd->add_option("--layers", a->layers, "the layered EXR (overrides output.layers and -o's), or none");
  cmd->add_option("--spp", a->spp, "samples per pixel [default: the scene's render.spp, else 16]")
      ->check(CLI::Range(1, kMaxSpp));
  cmd->add_option("--seed", a->seed, "random seed [default: the scene's render.seed, else 1]")->check(CLI::Range(0L, kMaxSeed));
  std::string help = "integrator:";
  for (const auto& e : integrator_registry()) help += fmt::format(" {} ({})", e.name, e.summary);
  cmd->add_option("--integrator", a->integrator, help);
  cmd->add_option("--irradiance", a->irradiance,
                  "irradiance mode of the irradiance integrator: " + quoted_choices(names_of(kIrradianceModes)) +
                      " [default: the scene's, else exact]")
      ->check(CLI::IsMember(names_of(kIrradianceModes)));
  cmd->add_option("--tonemap", a->tonemap,
                  "for PNG/JPEG: " + quoted_choices(names_of(kToneMaps)) + " [default: the scene's, else photo]")
      ->check(CLI::IsMember(names_of(kToneMaps)));
  cmd->add_flag("--resume", a->resume, "continue an interrupted render from its checkpoint (OUT.checkpoint)");
  cmd->add_option("--key", a->key, "tone-mapping key [default: adaptive_log 1, reinhard 0.18, linear 1]")->check(CLI::PositiveNumber);
  return [cmd, a] { return cmd->parsed() ? run_render(*a) : -1; };
}

}  // namespace insitu
