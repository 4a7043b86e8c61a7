// The render loop: for every pixel, spp camera samples at sub-pixel positions from the sampler's
// scrambled Sobol points (core/sampler.h), each traced by the integrator, in up to
// 8 passes over the image so that progress can report the noise reached. Tiles run in parallel on
// TBB; every sample's random numbers come from the counter-based hash and each pixel sums its
// samples over a fixed tree of sample indices (render/pixel_blocks.h), so the image does not
// depend on the number of threads or passes, or on how a split render was split. With a noise
// target, pixels stop between passes as they converge (render/adaptive.h).
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>

#include "core/camera.h"
#include "core/image.h"
#include "render/integrator.h"
#include "render/render_state.h"

namespace insitu {

// depth.Z where no sample met an object or the local scene: Cycles's background depth, finite so
// that every layer stays finite.
constexpr float kNoHitDepth = 1e10f;

// What the render loop itself reads: samples per pixel and the seed of the counter-based random
// numbers (the integrator reads its own parameters: src/integrators/registry.h).
// `stop`, when set (a signal handler, a host's cancel), ends the render after the pass under way:
// the layers are then the means over the samples taken (RenderLayers::spp_done).
// `stop_at_once`: the stop is also looked at before each sample, so that it takes effect within a
// sample's time whatever the spp (a tile of a pass at 2^20 spp is minutes). The tiles under way
// are left unfinished: their pixels done so far keep this pass's samples, the pixel under way
// none, and the state is no longer resumable (RenderState::resumable). The studio's stop, which
// keeps no checkpoint.
// `sample_begin`, `sample_end`: render only the samples [begin, end) of the spp (a part of a split
// render; end −1: spp).
// `noise_target` > 0: adaptive sampling (render/adaptive.h), each pixel stopping at that relative
// standard error, spp the most it takes; a whole render only (not a part of a split one).
struct RenderSettings {
  int spp = 16;
  std::uint64_t seed = 1;
  const std::atomic<bool>* stop = nullptr;
  int sample_begin = 0, sample_end = -1;
  double noise_target = 0;
  bool stop_at_once = false;
};

struct RenderLayers {
  Image objects;                        // RGB, premultiplied by coverage: mean over samples of radiance × coverage
  Image alpha;                          // 1 channel: mean coverage
  Image with_objects, without_objects;  // RGB: mean over samples of the catcher's radiance (0 off it)
  Image normal, albedo;                 // RGB: mean over the samples that met an object or a catcher
  Image depth;                          // 1 channel: camera-space z (metres along the optical axis, as Cycles's and
                                        // Nuke's Z) of what the samples met, averaged over those that met
                                        // something; kNoHitDepth where none did
  Image samples;   // 1 channel: samples taken in the pixel (fewer where adaptive sampling stopped it)
  Image variance;  // 1 channel: variance of the pixel's mean, luminance of O + W − N, estimated
                   // as if the samples were independent (an upper bound: they are
                   // scrambled Sobol points)
  // For the composite's choice between the ratio and the additive form (composite.h): variance
  // of the ratio of means W̄/N̄ and of the difference W̄ − N̄ (luminance), and the number of samples
  // that saw the catcher.
  Image ratio_variance, difference_variance, catcher_samples;
  int spp_done = 0;                   // samples per pixel taken (spp unless stopped; the most any pixel took)
  int sample_begin = 0;               // the first of them (a part of a split render, or parts merged)
  bool interrupted = false;           // stopped before spp
  double mean_relative_noise = 0;     // mean over changed pixels of √variance / value
  std::size_t nonfinite_samples = 0;  // zeroed and counted, never propagated
  double seconds = 0;
};

// Progress of a render: called once with fraction 0 when the sample loop starts, then from the
// rendering threads (serialized) with noise −1, and after each pass of samples with the noise
// reached (mean relative standard error over the pixels the render changed).
struct RenderProgress {
  double fraction = 0;
  int spp_done = 0;
  double noise = -1;
};
using ProgressFn = std::function<void(const RenderProgress&)>;

// The mean over pixels of the samples each took (the samples layer's mean).
double mean_spp(const RenderLayers& layers);

// The layers of a render's state: the means over the samples each pixel has (a part of a split
// render, or parts merged: render/checkpoint.h).
RenderLayers layers_from_state(const RenderState& state);

// With `state`, the render continues from it (a resumed checkpoint: its size and spp must be the
// camera's and the settings', else std::invalid_argument) and leaves in it where it ended.
RenderLayers render(const Camera& camera, const Integrator& integrator, const RenderSettings& settings,
                    const ProgressFn& progress = {}, RenderState* state = nullptr);

}  // namespace insitu
