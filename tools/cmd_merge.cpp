// insitu merge PART... -o OUT [--layers PATH|none] [--tonemap OP] [--key K] [--denoise] [--allow-partial]
//
// The parts of a split render (`insitu render --samples A:B`, issue 17) added into the image, the
// layers and the report that one render of all their samples gives, bit for bit: each pixel's
// sums are pairwise over aligned blocks of sample indices (render/pixel_blocks.h), and the parts'
// blocks are pushed in sample order as the render itself pushes them. The parts must be of one
// scene with the same inputs and settings, and cover the samples 0:spp without gap or overlap
// (--allow-partial: any adjoining range, whose report then says "interrupted": true); the scene is
// loaded again from the path and the overrides each part records, and its fingerprint must still
// be theirs. --denoise denoises the merged composite (output/denoise.h), as `render --denoise`
// does a whole render's: the parts hold the sums, never a denoised image.
#include <algorithm>
#include <cstdio>
#include <fmt/format.h>
#include <memory>

#include "commands.h"
#include "core/output_paths.h"
#include "render/checkpoint.h"
#include "render/pixel_blocks.h"
#include "render_args.h"
#include "scene/output_layers.h"
#include "scene/pipeline.h"

namespace insitu {
namespace {

struct MergeArgs {
  std::vector<std::string> parts;
  RenderArgs outputs;  // -o, --layers, --tonemap, --key, --denoise
  bool allow_partial = false;
};

struct Part {
  std::string path;
  StateFile file;
  PartRecord record;  // empty for a checkpoint
};

// The parts, read and sorted by their first sample; refused unless complete, of one scene and
// settings, and adjoining.
std::vector<Part> read_parts(const std::vector<std::string>& paths) {
  std::vector<Part> parts;
  for (const std::string& p : paths) {
    StateFile file = read_state_file(p);
    if (file.settings.empty() || file.state.noise_target > 0)
      throw InputError(p, "a checkpoint of an interrupted render, not a part (resume it)");
    PartRecord record = part_record_from_json(file.settings, p);
    parts.push_back({p, std::move(file), std::move(record)});
  }
  for (const Part& p : parts) {
    const RenderState& st = p.file.state;
    if (st.passes_done != render_passes(st.sample_end - st.sample_begin))
      throw InputError(p.path, "an unfinished part (render it again with --resume)");
    if (p.record.args_text != parts[0].record.args_text || p.file.fingerprint != parts[0].file.fingerprint)
      throw InputError(p.path, "a part of another scene, other inputs or other settings than " + parts[0].path);
  }
  std::sort(parts.begin(), parts.end(),
            [](const Part& a, const Part& b) { return a.file.state.sample_begin < b.file.state.sample_begin; });
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const RenderState &prev = parts[i - 1].file.state, &st = parts[i].file.state;
    if (st.sample_begin != prev.sample_end)
      throw InputError(parts[i].path, fmt::format("samples {}:{} do not follow {}'s {}:{} ({})", st.sample_begin,
                                                  st.sample_end, parts[i - 1].path, prev.sample_begin, prev.sample_end,
                                                  st.sample_begin < prev.sample_end ? "they overlap" : "a gap"));
  }
  return parts;
}

// The adjoining parts cover the render's samples 0:spp; else the missing range is named.
void require_all_samples(const std::vector<Part>& parts) {
  const RenderState &first = parts.front().file.state, &last = parts.back().file.state;
  const std::string advice = " (render the missing part, or merge what there is with --allow-partial)";
  if (first.sample_begin != 0)
    throw InputError(parts.front().path, fmt::format("samples 0:{} of the {} spp are in no part given{}",
                                                     first.sample_begin, first.spp, advice));
  if (last.sample_end != last.spp)
    throw InputError(parts.back().path, fmt::format("samples {}:{} of the {} spp are in no part given{}",
                                                    last.sample_end, last.spp, last.spp, advice));
}

// The state of one render of all the parts' samples.
RenderState merged_state(const std::vector<Part>& parts) {
  RenderState out = parts[0].file.state;
  out.sample_end = parts.back().file.state.sample_end;
  out.passes_done = render_passes(out.sample_end - out.sample_begin);
  out.spp_done = out.sample_end - out.sample_begin;
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const RenderState& st = parts[i].file.state;
    out.nonfinite += st.nonfinite;
    for (std::size_t p = 0; p < out.pixels.size(); ++p)
      for (const PixelSums& block : st.pixels[p]) push_block(out.pixels[p], out.sample_begin, block);
  }
  return out;
}

int run_merge(const MergeArgs& m) {
  const std::vector<Part> parts = read_parts(m.parts);
  if (!m.allow_partial) require_all_samples(parts);
  RenderArgs a = parts[0].record.args;
  a.output = m.outputs.output, a.layers = m.outputs.layers, a.tonemap = m.outputs.tonemap, a.key = m.outputs.key;
  a.denoise = m.outputs.denoise;
  const SceneSpec spec = render_spec(a);
  const LoadedScene scene = load_scene(spec);
  print_warnings(scene.warnings);
  if (render_fingerprint(scene) != parts[0].file.fingerprint)
    throw InputError(parts[0].path, "rendered from other inputs than " + spec.path + " has now (a file changed since)");
  const RenderState& first = parts[0].file.state;
  if (first.width != scene.camera.width || first.height != scene.camera.height || first.spp != spec.render.spp)
    throw InputError(parts[0].path, "of another image size or spp than " + spec.path);
  std::vector<NamedPath> inputs = loaded_scene_inputs(scene);
  for (const Part& p : parts) inputs.push_back({p.path, "the part " + p.path});
  check_outputs(inputs, scene_output_files(spec));
  const RenderState merged = merged_state(parts);
  // The report's timings: the parts' seconds added (the work, not the wall-clock time).
  double prepare_seconds = 0, render_seconds = 0;
  for (const Part& p : parts) prepare_seconds += p.record.prepare_seconds, render_seconds += p.record.render_seconds;
  RenderLayers layers = layers_from_state(merged);
  layers.seconds = render_seconds;
  layers.interrupted = merged.sample_begin != 0 || merged.sample_end != merged.spp;  // --allow-partial
  write_outputs(scene, finish_render(scene, std::move(layers), prepare_seconds));
  std::printf("%s\n", spec.output.image.c_str());
  if (!spec.output.layers.empty()) std::printf("%s\n", spec.output.layers.c_str());
  std::fprintf(stderr, "insitu: merged %zu parts, samples %d:%d of %d spp\n", parts.size(), merged.sample_begin,
               merged.sample_end, spec.render.spp);
  return 0;
}

}  // namespace

Command add_merge_command(CLI::App& app) {
  auto m = std::make_shared<MergeArgs>();
  CLI::App* cmd = app.add_subcommand("merge", "add the parts of a split render (render --samples A:B) into its image");
  cmd->add_option("parts", m->parts, "the part files, in any order")->required();
  cmd->add_option("-o,--output", m->outputs.output,
                  "the composite image (.png, .jpg, .exr, .tif); the layers and the "
                  "report follow it: OUT_STEM.layers.exr, OUT.report.json")
      ->required();
  cmd->add_option("--layers", m->outputs.layers, "the layered EXR (overrides -o's), or none");
  cmd->add_option("--tonemap", m->outputs.tonemap, "for PNG/JPEG: " + quoted_choices(names_of(kToneMaps)))
      ->check(CLI::IsMember(names_of(kToneMaps)));
  cmd->add_option("--key", m->outputs.key, "tone-mapping key")->check(CLI::PositiveNumber);
  cmd->add_flag("--denoise", m->outputs.denoise,
                "denoise the merged composite (docs/denoise.md) [default: the scene's denoise, else off]");
  cmd->add_flag("--allow-partial", m->allow_partial,
                "merge parts that do not cover all the render's samples (the report "
                "says \"interrupted\": true)");
  return [cmd, m] { return cmd->parsed() ? run_merge(*m) : -1; };
}

}  // namespace insitu
