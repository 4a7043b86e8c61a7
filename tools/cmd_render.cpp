// insitu render SCENE [-o OUT] [--layers PATH|none] [--spp N] [--integrator NAME] [--irradiance MODE]
//                     [--seed N] [--noise-target T] [--tonemap OP] [--key K] [--denoise] [--resume]
//                     [--samples A:B [--part PATH]]
//
// --noise-target T (render.noise_target) samples adaptively: each pixel stops at relative standard
// error T, spp the most it takes (render/adaptive.h); the report gives the histogram of spp.
//
// SIGINT or SIGTERM finishes the pass under way, writes the partial image, layers and report (its
// spp the samples taken), and a checkpoint beside the image (OUT.checkpoint, render/checkpoint.h),
// and exits 130; --resume continues from the checkpoint to the image an uninterrupted render gives,
// bit for bit. A second signal ends the process at once (no half-written file, the checkpoint as
// it was).
//
// --samples A:B renders a part of a split render (issue 17): only those sample indices of the spp,
// with the random numbers of a whole render, their sums written to a part file that `insitu
// merge` adds to the others' (cmd_merge.cpp).
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <memory>

#include "core/json_reader.h"
#include "core/output_paths.h"
#include "core/temp_files.h"
#include "render/checkpoint.h"
#include "commands.h"
#include "integrators/registry.h"
#include "scene/pipeline.h"
#include "progress.h"
#include "render_args.h"
#include "scene/output_layers.h"

namespace insitu {

void print_warnings(const Warnings& w) {
  for (const auto& item : w.items) std::fprintf(stderr, "insitu: warning: %s\n", item.c_str());
}

namespace {

// The render of samples [begin, end) (end −1: all), stoppable by SIGINT/SIGTERM and resumable
// from `state`.
RenderResult render_with_progress(const LoadedScene& scene, RenderState& state, int begin = 0, int end = -1) {
  Progress progress("render");
  std::string detail;
  const int samples = (end < 0 ? scene.spec.render.spp : end) - begin;
  arm_graceful_stop(true);
  RenderResult result =
      render_scene(scene,
                   [&](const RenderProgress& p) {
                     const bool pass_end = p.noise >= 0;
                     if (pass_end) detail = fmt::format("{}/{} spp, noise {:.1f}%", p.spp_done, samples, 100 * p.noise);
                     progress.update(p.fraction, detail, pass_end);
                   },
                   {&graceful_stop_flag(), &state, begin, end});
  arm_graceful_stop(false);
  return result;
}

// --samples A:B, within the render's spp.
std::pair<int, int> parse_sample_range(const std::string& text, int spp) {
  int begin = 0, end = 0, used = 0;
  if (std::sscanf(text.c_str(), "%d:%d%n", &begin, &end, &used) != 2 || used != int(text.size()))
    throw InputError("--samples " + text, "not a range of sample indices A:B (for example 0:16)");
  if (begin < 0 || end <= begin || end > spp)
    throw InputError("--samples " + text,
                     fmt::format("not within the render's {} samples per pixel (0 <= A < B <= {})", spp, spp));
  return {begin, end};
}

// A part of a split render (issue 17): samples [A, B) of render.spp, their sums written to the
// part file (render/checkpoint.h) for `insitu merge`; interrupted, a checkpoint beside the part.
int run_part(const RenderArgs& a, const SceneSpec& spec) {
  const auto [begin, end] = parse_sample_range(a.samples, spec.render.spp);
  if (spec.render.noise_target > 0)
    throw InputError("--samples " + a.samples,
                     "a part of a split render cannot stop its pixels by their noise: render "
                     "it without render.noise_target (--noise-target 0)");
  const std::string part =
      a.part.empty() ? fmt::format("{}.samples-{}-{}.part", spec.output.image, begin, end) : a.part;
  const std::string checkpoint = checkpoint_path(part);
  const LoadedScene scene = load_scene(spec);
  print_warnings(scene.warnings);
  check_outputs(loaded_scene_inputs(scene), {{part, "--part " + part}, {checkpoint, "the part's checkpoint"}});
  const std::uint64_t fingerprint = render_fingerprint(scene);
  RenderState state;
  if (a.resume) state = read_checkpoint(checkpoint, fingerprint);
  if (a.resume && (state.sample_begin != begin || state.sample_end != end))
    throw InputError(checkpoint, fmt::format("a checkpoint of samples {}:{}, not {}", state.sample_begin,
                                             state.sample_end, a.samples));
  const RenderResult result = render_with_progress(scene, state, begin, end);
  if (result.layers.interrupted) {
    write_checkpoint(checkpoint, state, fingerprint);
    std::fprintf(stderr, "insitu: interrupted after %d of %d spp: wrote %s (continue with --resume)\n",
                 result.layers.spp_done, end - begin, checkpoint.c_str());
    return 130;
  }
  const nlohmann::json record = {{"args", sum_args_json(a)},
                                 {"prepare_seconds", result.prepare_seconds},
                                 {"render_seconds", result.layers.seconds}};
  write_checkpoint(part, state, fingerprint, json_text(record));
  std::error_code ignored;
  std::filesystem::remove(checkpoint, ignored);
  std::printf("%s\n", part.c_str());
  std::fprintf(stderr, "insitu: %s, samples %d:%d of %d, integrator %s: load %.2f s, prepare %.2f s, render %.2f s\n",
               spec.path.c_str(), begin, end, spec.render.spp, spec.render.integrator.c_str(), scene.load_seconds,
               result.prepare_seconds, result.layers.seconds);
  return 0;
}

int run_render(const RenderArgs& a) {
  const SceneSpec spec = render_spec(a);
  if (!a.samples.empty()) return run_part(a, spec);
  if (!a.part.empty()) throw InputError("--part " + a.part, "a part file is written only with --samples A:B");
  LoadedScene scene = load_scene(spec);
  print_warnings(scene.warnings);
  const std::string checkpoint = checkpoint_path(spec.output.image);
  const std::uint64_t fingerprint = render_fingerprint(scene);
  RenderState state;
  if (a.resume) state = read_checkpoint(checkpoint, fingerprint);
  const RenderResult result = render_with_progress(scene, state);
  // The per-pixel sums serve only a resume: a complete render frees them before its outputs are
  // made (a 1920 × 1440 still's blocks are 487 MB, held beside the layers twice over).
  if (!result.layers.interrupted) state = RenderState();
  write_outputs(scene, result);
  if (result.layers.interrupted) {
    write_checkpoint(checkpoint, state, fingerprint);
    std::fprintf(stderr,
                 "insitu: interrupted after %d of %d spp: wrote the partial image and %s (continue with --resume)\n",
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
  if (spec.render.noise_target > 0)
    std::fprintf(stderr, "insitu: adaptive sampling to %.2f%%: %.1f spp on average, at most %d\n",
                 100 * spec.render.noise_target, mean_spp(result.layers), spec.render.spp);
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
  cmd->add_option("--noise-target", a->noise_target,
                  "adaptive sampling: each pixel stops at this relative standard error (0.01: 1 %), spp the most it "
                  "takes; 0: off [default: the scene's render.noise_target, else 0]")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--seed", a->seed, "random seed [default: the scene's render.seed, else 1]")
      ->check(CLI::Range(0L, kMaxSeed));
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
  cmd->add_flag("--denoise", a->denoise,
                "denoise the composite (docs/denoise.md): the changed pixels only, the layers as rendered "
                "[default: the scene's denoise, else off]");
  cmd->add_flag("--resume", a->resume, "continue an interrupted render from its checkpoint (OUT.checkpoint)");
  cmd->add_option("--samples", a->samples,
                  "A:B: render only the samples A to B-1 of the spp, as a part of a split render, and write their sums "
                  "to the part file instead of the image (merge the parts with `insitu merge`)");
  cmd->add_option("--part", a->part, "the part file of --samples [default: OUT.samples-A-B.part]");
  cmd->add_option("--key", a->key, "tone-mapping key [default: adaptive_log 1, reinhard 0.18, linear 1]")
      ->check(CLI::PositiveNumber);
  return [cmd, a] { return cmd->parsed() ? run_render(*a) : -1; };
}

}  // namespace insitu
