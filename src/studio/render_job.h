// The light and render panel's work: one render at a time, on its
// own thread, of the scene file as it is when the render starts.
//
// A render loads the scene with the library (load_scene: the light recovered as the CLI recovers
// it), then renders with render_scene. The light's previews (the radiance cube and its exact
// irradiance E/π, unfolded, at one exposure) are made when the page first asks for them. After
// each pass of samples the render loop calls back, its threads idle; the composite of the samples
// so far (layers_from_state + finish_render) is published then, with the noise figure the loop
// reports (mean relative standard error over the pixels the render changes). So the page sees the
// render converge pass by pass, and the last image is the one `insitu render` would write. An
// adaptive render's passes are short (61 at 1024 spp, render/render_state.h), and a composite
// costs about a pass at catalogue size: an image is published after the first pass and after each
// pass that reaches a new eighth of the planned samples (every pass of a fixed render), and at the
// end.
//
// Each integrator's latest image is kept in its own slot ("path", "realtime", ...), linear and
// photo-encoded, so the page can tone map either again (adaptive_log's key and bias) without
// rendering, and flip between the scene's integrator and `realtime` (the legacy path, A/B).
#pragma once
#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/image.h"
#include "core/json_reader.h"
#include "light/cubemap.h"
#include "output/settings.h"

namespace insitu {

struct LoadedScene;
struct RenderResult;

// Whether the image after a pass that reached `spp_done` of `spp` samples is published, the last
// one published being at `shown` samples (0: none yet): the first and the last always, and in
// between at each new eighth of the samples while making the images so far (`image_seconds`: the
// composite and the denoiser, which the sample loop waits for) has taken at most kImageShare of
// the sample loop's own time (`loop_seconds`). The demo's 640 × 480 image is denoised in 2.3 s
// where a pass of a 16-spp preview renders in 0.9 s: each pass's image had made the preview 26 s
// instead of 9; so it shows 3 of the 8, and a 144-spp render all 8.
inline constexpr double kImageShare = 0.5;
inline bool publish_after_pass(int spp_done, int shown, int spp, double loop_seconds = 0, double image_seconds = 0) {
  if (shown == 0 || spp_done >= spp) return true;
  return long(spp_done) * 8 / spp > long(shown) * 8 / spp && image_seconds <= kImageShare * loop_seconds;
}

class RenderJob {
 public:
  explicit RenderJob(std::string scene_path) : scene_path_(std::move(scene_path)) {}
  ~RenderJob() { stop(); }
  RenderJob(const RenderJob&) = delete;
  RenderJob& operator=(const RenderJob&) = delete;

  // Starts a render with `integrator` ("": the scene's) and `spp` (0: the scene's), stopping one
  // under way first. `denoise`: the images shown are denoised (output/denoise.h); what
  // save_outputs writes follows the scene file's `denoise`, as `insitu render` does.
  void start(const std::string& integrator, int spp, bool denoise = true);
  // Stops the render under way and waits for it: at once, within a sample, whatever the spp
  // (RenderSettings::stop_at_once); the image keeps the samples taken.
  void stop();
  // {"state": "idle" | "loading" | "rendering" | "done" | "stopped" | "error", "integrator",
  //  "fraction", "spp_done", "spp", "noise", "passes", "seconds", "error": {"where", "what"},
  //  "slots": {name: {"spp_done", "spp", "noise", "seconds", "done", "passes"}}, "light": bool}
  json status() const;
  // The latest image of slot `name`, tone mapped by `tonemap` (photo: the composite as encoded
  // through the photo's own curve), as PNG; nullopt when that slot has no image yet.
  std::optional<std::string> png(const std::string& name, const ToneMapSettings& tonemap) const;
  // The light's previews as PNG (`irradiance`: E/π; else the radiance), once a scene has loaded:
  // made on the first request for that scene's cube.
  std::optional<std::string> light_png(bool irradiance) const;
  // Writes the last finished render of the scene's own integrator to the scene's outputs, as
  // `insitu render` does (write_outputs: atomic, never over an input); their paths. Throws
  // InputError when there is none yet.
  std::vector<std::string> save_outputs() const;
  // What save_outputs would write (image, layers, report), and the spp of the render it would
  // save. Throws InputError when there is no finished render yet.
  std::vector<std::string> output_paths(int* spp = nullptr) const;

 private:
  struct Slot {
    Image linear, encoded, clipped_photo;  // clipped_photo: any tone map but photo may show the slot
    int spp_done = 0, spp = 0, passes = 0;
    double noise = -1, seconds = 0;
    bool done = false;
  };
  void run(const std::string& integrator, int spp, bool denoise);
  void load_and_render(const std::string& integrator, int spp, bool denoise);
  void stop_worker();  // with control_ held
  void publish(const std::string& name, Slot slot);
  static Slot final_image(const LoadedScene& scene, const RenderResult& last, bool denoise, const Slot* shown);

  std::string scene_path_;
  std::mutex control_;  // serializes start() and stop() (two tabs may press at once)
  std::thread worker_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;  // guards everything below
  std::string state_ = "idle", integrator_;
  double fraction_ = 0;
  std::optional<json> error_;
  std::map<std::string, Slot> slots_;
  std::shared_ptr<const CubeMap> light_cube_;  // the latest loaded scene's environment (a copy)
  struct LightPreview {
    std::shared_ptr<const CubeMap> environment;  // the cube they show
    std::string cube_png, irradiance_png;
  };
  mutable std::mutex light_mutex_;  // guards light_ (made outside mutex_: status stays answered)
  mutable std::optional<LightPreview> light_;
  struct Finished;  // a scene and its finished render, for save_outputs
  std::shared_ptr<const Finished> finished_;
  std::shared_ptr<const Finished> finished() const;  // finished_, or InputError when none yet
};

}  // namespace insitu
