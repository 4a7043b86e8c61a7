// insitu.h: rendering, cancellation and the results.
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>

#include "api/api_internal.h"
#include "core/json_reader.h"
#include "core/output_paths.h"
#include "core/file_check.h"
#include "render/checkpoint.h"

using namespace insitu;
using insitu::api::ApiMisuse;
using insitu::api::guarded;
using insitu::api::not_null;
using insitu::api::require;

namespace {

// The C callback as the renderer's progress function: elapsed and remaining time added; a
// nonzero return raises the scene's cancel flag.
ProgressFn progress_adapter(insitu_progress_fn fn, void* user, int spp, std::atomic<bool>& cancel) {
  if (!fn) return {};
  const auto start = std::chrono::steady_clock::now();
  return [=, &cancel](const RenderProgress& p) {
    insitu_progress out{};
    out.spp_done = p.spp_done;
    out.spp_planned = spp;
    out.fraction = p.fraction;
    out.noise = p.noise;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out.seconds_left = p.fraction > 0 ? out.seconds * (1 - p.fraction) / p.fraction : -1.0;
    if (fn(&out, user) != 0) cancel = true;
  };
}

const OutputLayer& layer_named(const insitu_result& r, const char* name) {
  const std::string n = not_null(name, "the layer name");
  for (const OutputLayer& l : r.layers)
    if (l.name == n) return l;
  std::string names;
  for (const OutputLayer& l : r.layers) names += (names.empty() ? "" : ", ") + l.name;
  throw ApiMisuse(fmt::format("no layer '{}' (the layers: {})", n, names));
}

}  // namespace

extern "C" {}  // extern "C"

namespace {

// A render, from a checkpoint when `checkpoint` names one (then written when cancelled, removed
// when done: as `insitu render --resume`).
insitu_status render(insitu_scene* scene, const char* checkpoint, insitu_progress_fn progress, void* user,
                     insitu_result** result) {
  bool cancelled = false;
  const insitu_status st = guarded([&] {
    insitu_scene& s = require(scene, "the scene");
    require(result, "the result pointer");
    *result = nullptr;
    const LoadedScene& l = insitu::api::loaded(s);
    RenderState state;
    if (checkpoint) check_outputs(loaded_scene_inputs(l), {{checkpoint, "the checkpoint"}});
    const std::uint64_t fingerprint = checkpoint ? render_fingerprint(l) : 0;
    if (checkpoint && exists_quietly(checkpoint)) state = read_checkpoint(checkpoint, fingerprint);
    s.cancel = false;
    auto r = std::make_unique<insitu_result>();
    r->scene = s.loaded;
    r->result = render_scene(l, progress_adapter(progress, user, l.spec.render.spp, s.cancel), {&s.cancel, &state});
    if (checkpoint && r->result.layers.interrupted) write_checkpoint(checkpoint, state, fingerprint);
    if (checkpoint && !r->result.layers.interrupted) std::filesystem::remove(checkpoint);
    r->layers = output_layers(l, r->result);
    r->report = json_text(render_report(l, r->result), 2) + "\n";
    cancelled = r->result.layers.interrupted;
    *result = r.release();
  });
  return st == INSITU_OK && cancelled ? INSITU_CANCELLED : st;
}

}  // namespace

extern "C" {

insitu_status insitu_render(insitu_scene* scene, insitu_progress_fn progress, void* user, insitu_result** result) {
  return render(scene, nullptr, progress, user, result);
}

insitu_status insitu_render_resumable(insitu_scene* scene, const char* checkpoint_path, insitu_progress_fn progress,
                                      void* user, insitu_result** result) {
  if (!checkpoint_path) return guarded([] { throw insitu::api::ApiMisuse("the checkpoint path is NULL"); });
  return render(scene, checkpoint_path, progress, user, result);
}

void insitu_scene_cancel(insitu_scene* scene) {
  if (scene) scene->cancel = true;
}

void insitu_result_free(insitu_result* result) { delete result; }
int insitu_result_width(const insitu_result* r) { return r ? r->result.composite_linear.width : 0; }
int insitu_result_height(const insitu_result* r) { return r ? r->result.composite_linear.height : 0; }
int insitu_result_spp(const insitu_result* r) { return r ? r->result.layers.spp_done : 0; }
int insitu_result_cancelled(const insitu_result* r) { return r && r->result.layers.interrupted ? 1 : 0; }
const char* insitu_result_report(const insitu_result* r) { return r ? r->report.c_str() : ""; }
int insitu_result_layer_count(const insitu_result* r) { return r ? int(r->layers.size()) : 0; }

const char* insitu_result_layer_name(const insitu_result* r, int index) {
  if (!r || index < 0 || std::size_t(index) >= r->layers.size()) return nullptr;
  return r->layers[std::size_t(index)].name.c_str();
}

insitu_status insitu_result_layer(const insitu_result* result, const char* name, const float** data, int* channels) {
  return guarded([&] {
    const OutputLayer& l = layer_named(require(result, "the result"), name);
    require(data, "the data pointer") = l.image.data.data();
    if (channels) *channels = l.image.channels;
  });
}

insitu_status insitu_result_copy_layer(const insitu_result* result, const char* name, float* buffer, size_t floats) {
  return guarded([&] {
    const OutputLayer& l = layer_named(require(result, "the result"), name);
    require(buffer, "the buffer");
    if (floats < l.image.data.size())
      throw ApiMisuse(fmt::format("the buffer holds {} floats, the layer '{}' needs {} ({}x{}x{})", floats, l.name,
                                  l.image.data.size(), l.image.width, l.image.height, l.image.channels));
    std::memcpy(buffer, l.image.data.data(), l.image.data.size() * sizeof(float));
  });
}

insitu_status insitu_result_write(const insitu_result* result, const char* image_path, const char* layers_path) {
  return guarded([&] {
    const insitu_result& r = require(result, "the result");
    OutputSpec out = r.scene->spec.output;
    out.image = not_null(image_path, "the image path");
    const std::string ext = lower_extension(out.image);
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".exr" && ext != ".tif" && ext != ".tiff")
      throw InputError(out.image, "unsupported extension '" + ext + "' (use .png, .jpg, .exr, .tif)");
    out.layers = layers_path ? layers_path : "";
    if (!out.layers.empty() && lower_extension(out.layers) != ".exr")
      throw InputError(out.layers, "the layers are a multi-layer EXR: use .exr");
    write_outputs(*r.scene, r.result, &out);
  });
}

}  // extern "C"
