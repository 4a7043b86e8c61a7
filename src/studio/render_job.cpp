#include "studio/render_job.h"

#include <chrono>

#include "core/stop.h"
#include "light/irradiance.h"
#include "light/preview.h"
#include "output/composite.h"
#include "output/tonemap.h"
#include "scene/pipeline.h"
#include "studio/preview_png.h"

namespace insitu {

struct RenderJob::Finished {
  std::shared_ptr<const LoadedScene> scene;
  RenderResult result;
};

namespace {

json error_json(const std::string& where, const std::string& what) { return {{"where", where}, {"what", what}}; }

}  // namespace

void RenderJob::start(const std::string& integrator, int spp, bool denoise) {
  const std::lock_guard<std::mutex> control(control_);
  stop_worker();
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    state_ = "loading", integrator_ = integrator, fraction_ = 0, error_.reset();
  }
  stop_ = false;
  worker_ = std::thread([this, integrator, spp, denoise] { run(integrator, spp, denoise); });
}

void RenderJob::stop() {
  const std::lock_guard<std::mutex> control(control_);
  stop_worker();
}

void RenderJob::stop_worker() {
  stop_ = true;
  if (worker_.joinable()) worker_.join();
}

void RenderJob::publish(const std::string& name, Slot slot) {
  const std::lock_guard<std::mutex> lock(mutex_);
  slots_[name] = std::move(slot);
}

// The render's last image, denoised or not as asked whatever the scene file says for the saved
// one. `shown`: the image of the last pass, published from these same samples (the last pass
// publishes its image as every pass does), taken as it is: made again, it would be the same
// image for a second denoiser's time.
RenderJob::Slot RenderJob::final_image(const LoadedScene& scene, const RenderResult& last, bool denoise,
                                       const Slot* shown) {
  Slot slot;
  if (shown) {
    slot.linear = shown->linear, slot.encoded = shown->encoded;
  } else if (last.denoise_asked != denoises(scene, denoise)) {
    RenderResult redone = finish_render(scene, last.layers, 0, denoise);
    slot.linear = std::move(redone.composite_linear), slot.encoded = std::move(redone.composite_encoded);
  } else {
    slot.linear = last.composite_linear, slot.encoded = last.composite_encoded;
  }
  slot.clipped_photo = clipped_photo_weight(last.layers, scene.photo);
  return slot;
}

// Load, preview the light, render pass by pass.
void RenderJob::load_and_render(const std::string& integrator, int spp, bool denoise) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  SceneSpec spec = parse_scene_file(scene_path_);
  if (!integrator.empty()) spec.render.integrator = integrator;
  if (spp > 0) spec.render.spp = spp;
  const auto loaded = std::make_shared<const LoadedScene>(load_scene(spec, {}, nullptr, &stop_));
  const LoadedScene& scene = *loaded;
  const std::string name = scene.integrator.entry->name;
  auto cube = std::make_shared<const CubeMap>(scene.environment);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    light_cube_ = std::move(cube);  // its previews are made when the page asks (light_png)
    state_ = "rendering", integrator_ = name;
    slots_[name] = Slot{};  // this integrator's image is the new render's from its first pass on
  }
  RenderState state;
  const RenderControl control{&stop_, &state, 0, -1, true};  // a stop takes effect at once
  int passes = 0, shown = 0;                                 // images published, and the samples of the last
  Slot shown_slot;                                           // the last one published
  double loop_start = -1, image_seconds = 0;                 // the sample loop's first progress (after the preparation)
  const auto progress = [&](const RenderProgress& p) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      fraction_ = p.fraction;
    }
    if (loop_start < 0) loop_start = seconds();
    if (p.noise < 0) return;  // within a pass, from the rendering threads
    const double start = seconds();
    if (!publish_after_pass(p.spp_done, shown, spec.render.spp, start - loop_start - image_seconds, image_seconds))
      return;
    shown = p.spp_done;
    // Between passes: the threads are idle and the state holds the samples so far.
    RenderResult r = finish_render(scene, layers_from_state(state), 0, denoise);
    image_seconds += seconds() - start;
    shown_slot = {std::move(r.composite_linear),
                  std::move(r.composite_encoded),
                  clipped_photo_weight(r.layers, scene.photo),
                  p.spp_done,
                  spec.render.spp,
                  ++passes,
                  p.noise,
                  seconds(),
                  false};
    publish(name, shown_slot);
  };
  const RenderResult last = render_scene(scene, progress, control);
  Slot final_slot =
      final_image(scene, last, denoise, passes > 0 && shown == last.layers.spp_done ? &shown_slot : nullptr);
  final_slot.spp_done = last.layers.spp_done, final_slot.spp = spec.render.spp, final_slot.passes = passes;
  final_slot.noise = last.layers.mean_relative_noise, final_slot.seconds = seconds();
  final_slot.done = !last.layers.interrupted;
  if (passes > 0 || !last.layers.interrupted) publish(name, std::move(final_slot));  // stopped before a pass: nothing
  auto finished = last.layers.interrupted || !integrator.empty()
                      ? nullptr
                      : std::make_shared<const Finished>(Finished{loaded, last});
  const std::lock_guard<std::mutex> lock(mutex_);
  state_ = last.layers.interrupted ? "stopped" : "done";
  if (finished) finished_ = std::move(finished);
}

// The worker: bad input ends it with the library's message (`error`); nothing escapes the thread.
void RenderJob::run(const std::string& integrator, int spp, bool denoise) {
  try {
    load_and_render(integrator, spp, denoise);
  } catch (const Stopped&) {  // during loading or the integrator's preparation: no image
    const std::lock_guard<std::mutex> lock(mutex_);
    state_ = "stopped";
  } catch (const InputError& e) {
    const std::lock_guard<std::mutex> lock(mutex_);
    state_ = "error", error_ = error_json(e.where(), e.message());
  } catch (const std::exception& e) {
    const std::lock_guard<std::mutex> lock(mutex_);
    state_ = "error", error_ = error_json("", std::string("internal error: ") + e.what());
  }
}

json RenderJob::status() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  json slots = json::object();
  for (const auto& [name, s] : slots_)
    slots[name] = {{"spp_done", s.spp_done},         {"spp", s.spp},   {"noise", s.noise},
                   {"seconds", s.seconds},           {"done", s.done}, {"passes", s.passes},
                   {"image", !s.linear.data.empty()}};
  return {{"state", state_},
          {"integrator", integrator_},
          {"fraction", fraction_},
          {"slots", slots},
          {"error", error_ ? *error_ : json(nullptr)},
          {"light", light_cube_ != nullptr}};
}

std::optional<std::string> RenderJob::png(const std::string& name, const ToneMapSettings& tonemap) const {
  Image image, clipped;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = slots_.find(name);
    if (it == slots_.end() || it->second.linear.data.empty()) return std::nullopt;
    image = tonemap.op == ToneMap::kPhoto ? it->second.encoded : it->second.linear;
    if (tonemap.op != ToneMap::kPhoto) clipped = it->second.clipped_photo;
  }
  return display_png(tonemap.op == ToneMap::kPhoto ? image : insitu::tonemap(image, tonemap, &clipped));
}

// The irradiance preview's radiance, per face: E within 7.1 ∫ L dω / 128 = 5.5 % of ∫ L dω
// (exact_irradiance_cube's bound; 4.6·10⁻⁴ at most on the shared HDRIs), a display's precision. The
// exact integral's time per direction grows with the face.
constexpr int kLightPreviewFace = 128;

// The light as the latest render uses it: the cube, and its exact irradiance over π, at one
// exposure. Made on the page's first request, not before the render: the exact irradiance of the
// demo's cube takes about 2 s (half of the sanitized studio tests' time), and a render stopped or
// failed before the page asks needs none. Kept while the cube stays the same texels, so an A/B
// render of the same light makes none.
std::optional<std::string> RenderJob::light_png(bool irradiance) const {
  std::shared_ptr<const CubeMap> cube;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    cube = light_cube_;
  }
  if (!cube) return std::nullopt;
  const std::lock_guard<std::mutex> lock(light_mutex_);
  if (!light_ || !light_->environment->same_texels(*cube)) {
    const CubeMap& L = *cube;
    const double exposure = preview_exposure(L);
    // E/π at 32² per face, exact over the radiance box-averaged to kLightPreviewFace per face.
    light_ =
        LightPreview{cube, display_png(cube_cross_preview(L, exposure)),
                     display_png(cube_cross_preview(exact_irradiance_cube(L, 32, kLightPreviewFace), exposure / kPi))};
  }
  return irradiance ? light_->irradiance_png : light_->cube_png;
}

namespace {

std::vector<std::string> paths_of(const OutputSpec& out) {
  std::vector<std::string> paths = {out.image};
  if (!out.layers.empty()) paths.push_back(out.layers);
  paths.push_back(report_path(out.image));
  return paths;
}

}  // namespace

std::shared_ptr<const RenderJob::Finished> RenderJob::finished() const {
  std::shared_ptr<const Finished> f;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    f = finished_;
  }
  if (!f) throw InputError("", "no finished render of the scene's own integrator to save yet");
  return f;
}

std::vector<std::string> RenderJob::output_paths(int* spp) const {
  const auto f = finished();
  if (spp) *spp = f->result.layers.spp_done;
  return paths_of(f->scene->spec.output);
}

std::vector<std::string> RenderJob::save_outputs() const {
  const auto f = finished();
  write_outputs(*f->scene, f->result);
  return paths_of(f->scene->spec.output);
}

}  // namespace insitu
