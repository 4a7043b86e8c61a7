#include "render/render.h"

#include "render/adaptive.h"
#include "render/pixel_blocks.h"
#include "render/pixel_variance.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <stdexcept>

namespace insitu {

namespace {

// Variance of the ratio of means R = w̄/n̄ by the delta method, with the correlation of w and n
// (Cochran 1977, §6.3): Var(R) ≈ Σ(wᵢ − R nᵢ)² / (k (k − 1) n̄²) over k samples. Since
// w̄ − R n̄ = 0, Σ(wᵢ − R nᵢ)² = M_ww − 2R M_wn + R² M_nn in the centred moments.
double ratio_variance(const PixelSums& p, int k) {
  const double w = sum_w(p), n = sum_n(p);
  if (k < 2 || !(n > 0)) return 0.0;
  const double R = w / n, n_mean = n / k;
  const double d2 = std::max(0.0, double(p.m_ww) - 2 * R * double(p.m_wn) + R * R * double(p.m_nn));
  return d2 / (double(k) * (k - 1) * n_mean * n_mean);
}

// Variance of the mean of w − n: Σ((w − n) − (w̄ − n̄))² / (k (k − 1)), that is
// (M_ww − 2 M_wn + M_nn) / (k (k − 1)).
double difference_variance(const PixelSums& p, int k) {
  if (k < 2) return 0.0;
  const double m2 = double(p.m_ww) - 2 * double(p.m_wn) + double(p.m_nn);
  return std::max(0.0, m2 / (double(k) * (k - 1)));
}

// Mean over pixels the render changed (an object covers them or the catcher's estimates differ)
// of √variance relative to the pixel's value. Changed pixels of variance 0 count as 0, so that the
// set of pixels, and with it the figure, does not jump from pass to pass. A pixel adds its
// relative error to `noise` and 1 to `changed` (render/render_state.h's changed_pixel).
void add_relative_noise(const PixelSums& p, double& noise, long& changed) {
  const int n = p.samples;
  if (n == 0 || !changed_pixel(p)) return;
  const double v = variance_of_mean(p);
  const double value = pixel_value(p);
  if (value <= 0) return;
  noise += std::sqrt(v) / value;
  ++changed;
}

// Summed row by row (each row in x order), then the rows in order: the same bits however the rows
// are shared among threads. `pixel(i)` gives pixel i's sums.
template <class PixelAt>
double mean_relative_noise(int w, int h, const PixelAt& pixel) {
  std::vector<double> row_noise(std::size_t(h), 0.0);
  std::vector<long> row_changed(std::size_t(h), 0);
  auto row = [&](int y) {
    for (int x = 0; x < w; ++x)
      add_relative_noise(pixel(std::size_t(y) * std::size_t(w) + std::size_t(x)), row_noise[std::size_t(y)],
                         row_changed[std::size_t(y)]);
  };
  tbb::parallel_for(0, h, row);
  double noise = 0;
  long changed = 0;
  for (int y = 0; y < h; ++y) noise += row_noise[std::size_t(y)], changed += row_changed[std::size_t(y)];
  return changed > 0 ? noise / double(changed) : 0.0;
}

// The same figure from the state, each pixel's blocks folded where it is read. The progress report
// after every pass used to fold the whole image into a new array first, 46 MB for the demo: 8
// passes of a 16-spp `realtime` render spent more time there, in page faults, than in rendering.
double mean_relative_noise(const RenderState& st) {
  return mean_relative_noise(st.width, st.height, [&](std::size_t i) { return fold_blocks(st.pixels[i]); });
}

// Sample s of pixel (x, y): a position in the pixel from the sampler's first pair of numbers —
// the Sobol points of core/sampler.h, so that every power-of-two prefix of a pixel's samples (a
// pass's) covers it evenly, one point in each of n cells of every shape.
Ray jittered_ray(const Camera& camera, int x, int y, Sampler& sampler) {
  const float jx = sampler.next(), jy = sampler.next();
  return camera.ray({double(x) + jx, double(y) + jy});
}

// One camera sample as a leaf (its centred moments are 0); a non-finite one is refused (false)
// and the leaf stays zero. depth.Z is camera-space z: the distance t along the unit ray times
// d · (optical axis).
bool sample_leaf(PixelSums& p, const CameraSample& cs, const Ray& ray, const Vec3f& axis_world) {
  p.samples = 1;
  if (!cs.radiance.allFinite() || !std::isfinite(cs.coverage) || !cs.with_objects.allFinite() ||
      !cs.without_objects.allFinite())
    return false;
  p.objects = cs.radiance * cs.coverage;
  p.coverage = cs.coverage;
  p.with = cs.with_objects;
  p.without = cs.without_objects;
  p.catcher = (luminance(cs.with_objects) != 0 || luminance(cs.without_objects) != 0);
  if (cs.depth > 0) {
    p.met = 1;
    p.normal = cs.normal;
    p.albedo = cs.albedo;
    p.depth = float(double(cs.depth) * double(ray.dir.dot(axis_world)));
  }
  return true;
}

// Pixel (x, y)'s layers: means over its samples (normal, albedo and depth over those that met
// something); a pixel without samples (a cancelled first pass) stays 0.
void set_pixel_layers(RenderLayers& out, int x, int y, const PixelSums& p) {
  const int spp = p.samples;
  *out.samples.at(x, y) = float(spp);
  if (spp == 0) return;
  out.objects.set_rgb(x, y, p.objects / float(spp));
  *out.alpha.at(x, y) = p.coverage / float(spp);
  out.with_objects.set_rgb(x, y, p.with / float(spp));
  out.without_objects.set_rgb(x, y, p.without / float(spp));
  if (p.met > 0) {
    out.normal.set_rgb(x, y, Rgb(p.normal.array() / float(p.met)));
    out.albedo.set_rgb(x, y, p.albedo / float(p.met));
    *out.depth.at(x, y) = p.depth / float(p.met);
  }
  *out.variance.at(x, y) = float(variance_of_mean(p));
  *out.ratio_variance.at(x, y) = float(ratio_variance(p, spp));
  *out.difference_variance.at(x, y) = float(difference_variance(p, spp));
  *out.catcher_samples.at(x, y) = float(p.catcher);
}

// The layers of the state, each pixel's blocks folded where it is read: no image-sized array of
// totals (46 MB for the demo, whose page faults were a third of a 1-spp `realtime` render).
RenderLayers layers_from_blocks(const RenderState& st) {
  const int w = st.width, h = st.height;
  RenderLayers out;
  out.objects = Image(w, h, 3);
  out.alpha = Image(w, h, 1);
  out.with_objects = Image(w, h, 3);
  out.without_objects = Image(w, h, 3);
  out.normal = Image(w, h, 3);
  out.albedo = Image(w, h, 3);
  out.depth = Image(w, h, 1, kNoHitDepth);
  out.samples = Image(w, h, 1);
  out.variance = Image(w, h, 1);
  out.ratio_variance = Image(w, h, 1);
  out.difference_variance = Image(w, h, 1);
  out.catcher_samples = Image(w, h, 1);
  tbb::parallel_for(0, h, [&](int y) {  // rows in parallel: each pixel's own, in any order
    for (int x = 0; x < w; ++x) set_pixel_layers(out, x, y, fold_blocks(st.pixels[std::size_t(y) * w + x]));
  });
  out.mean_relative_noise = mean_relative_noise(st);
  return out;
}

// One pass: samples [s0, s1) of every pixel, tiles in parallel.
struct PassContext {
  const Camera& camera;
  const Integrator& integrator;
  const RenderSettings& settings;
  const ProgressFn& progress;
  int spp, first;  // first: the first sample of the range rendered
  Vec3f axis_world;
  std::vector<PixelBlocks>& pixels;
  const std::vector<std::uint8_t>& stopped;  // by adaptive sampling (empty when it is off)
  std::atomic<std::size_t>& nonfinite;
  std::atomic<long>& area_done;
  std::mutex& progress_mutex;
  double total_work;
};

// Whether a stop at once (RenderSettings::stop_at_once) has come.
bool stopped_at_once(const RenderSettings& s) {
  return s.stop_at_once && s.stop && s.stop->load(std::memory_order_relaxed);
}

// Samples [s0, s1) of the pixels of one tile; false when a stop at once left it unfinished.
bool render_tile(const PassContext& c, int tile, int s0, int s1) {
  const int w = c.camera.width, h = c.camera.height, across = tiles_across(w);
  const int x0 = (tile % across) * kTilePixels, y0 = (tile / across) * kTilePixels;
  const int x1 = std::min(w, x0 + kTilePixels), y1 = std::min(h, y0 + kTilePixels);
  std::size_t local_nonfinite = 0;
  // The pass's samples of a pixel are stacked here first (their canonical blocks of [s0, s1):
  // alignment is by absolute sample index, so the same blocks, with the same bits, as pushed one
  // by one), merged onto a copy of the pixel's in `merged`, and copied back within the capacity
  // start_state reserved: a pass allocates nothing, where pushing the samples one by one and
  // shrinking reallocated every pass (malloc's lock, taken by both threads, made a 16-spp
  // `realtime` render slower on 2 threads than on 1). Pushing onto the pixel's blocks directly
  // overflows that capacity by one before the merge and reallocates: 0.9 s -> 1.65 s.
  thread_local PixelBlocks pass_blocks, merged;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const std::uint64_t pixel = std::uint64_t(y) * std::uint64_t(w) + std::uint64_t(x);
      if (!c.stopped.empty() && c.stopped[pixel]) continue;
      pass_blocks.clear();
      for (int s = s0; s < s1; ++s) {
        if (stopped_at_once(c.settings)) {  // this pixel's samples of the pass are dropped
          c.nonfinite += local_nonfinite;
          return false;
        }
        Sampler sampler(c.settings.seed, pixel, std::uint64_t(s));
        const Ray ray = jittered_ray(c.camera, x, y, sampler);
        PixelSums leaf;
        if (!sample_leaf(leaf, c.integrator.sample(ray, sampler), ray, c.axis_world)) ++local_nonfinite;
        push_block(pass_blocks, s0, leaf);
      }
      PixelBlocks& blocks = c.pixels[pixel];
      merged.assign(blocks.begin(), blocks.end());
      for (const PixelSums& b : pass_blocks) push_block(merged, c.first, b);
      blocks.assign(merged.begin(), merged.end());
    }
  c.nonfinite += local_nonfinite;
  if (c.progress) {
    const long done = c.area_done += long(y1 - y0) * long(x1 - x0) * (s1 - s0);
    std::lock_guard<std::mutex> lock(c.progress_mutex);
    c.progress({double(done) / c.total_work, s0 - c.first, -1.0});
  }
  return true;
}

// One pass: samples [s0, s1) of every pixel. The threads take tiles in order from *tiles_done
// on and look at the stop flag before taking one, so that, stopped, the pass has done exactly the
// tiles [0, *tiles_done), each whole: a resumed render carries on from there, bit for bit.
// Returns whether the pass is complete.
bool run_pass(const PassContext& c, int s0, int s1, int& tiles_done, bool& resumable) {
  const int tiles = tiles_across(c.camera.width) * tiles_across(c.camera.height);
  std::atomic<int> next{tiles_done};
  std::atomic<bool> unfinished{false};
  const int workers = std::max(1, tbb::this_task_arena::max_concurrency());
  tbb::parallel_for(0, workers, [&](int) {
    while (!(c.settings.stop && c.settings.stop->load())) {
      const int tile = next++;
      if (tile >= tiles) break;
      if (!render_tile(c, tile, s0, s1)) unfinished = true;
    }
  });
  if (unfinished) resumable = false;
  tiles_done = std::min(tiles, next.load());
  if (tiles_done < tiles) return false;
  tiles_done = 0;
  return true;
}

// Every pixel's room for the most blocks it holds at the end of any pass: the memory it reaches at
// that pass anyway, taken once rather than reallocated pass after pass.
void reserve_blocks(RenderState& st) {
  int most = 1;
  for (int k = 1; k <= plan_passes(st); ++k)
    most = std::max(most, canonical_count(st.sample_begin, plan_pass_start(st, k)));
  tbb::parallel_for(std::size_t(0), st.pixels.size(), [&](std::size_t i) { st.pixels[i].reserve(std::size_t(most)); });
}

// The state to start from: a fresh one, or the caller's (checked against the plan).
void start_state(RenderState& st, int w, int h, int spp, int begin, int end, double noise_target) {
  const std::size_t n = std::size_t(w) * std::size_t(h);
  if (!st.resumable)
    throw std::invalid_argument("render: the state was stopped within its tiles and cannot be resumed");
  if (st.passes_done == 0 && st.pixels.empty()) {
    st = RenderState{w,
                     h,
                     spp,
                     begin,
                     end,
                     0,
                     0,
                     0,
                     0,
                     std::vector<PixelBlocks>(n),
                     noise_target,
                     std::vector<std::uint8_t>(noise_target > 0 ? n : 0, 0)};
    reserve_blocks(st);
    return;
  }
  if (st.noise_target != noise_target || st.stopped.size() != (noise_target > 0 ? n : 0))
    throw std::invalid_argument("render: the state to resume is of another noise target");
  if (st.width != w || st.height != h || st.spp != spp || st.sample_begin != begin || st.sample_end != end ||
      st.pixels.size() != std::size_t(w) * h || st.passes_done < 0 || st.passes_done > plan_passes(st) ||
      st.tiles_done < 0 || st.tiles_done >= long(tiles_across(w)) * long(tiles_across(h)))
    throw std::invalid_argument("render: the state to resume is of another image size, spp or sample range");
}

// Each pixel's sum over the samples it has (its blocks folded), into `totals`: one image-sized
// array for all of an adaptive render's passes (61 at 1024 spp; 0.46 GB at 1920 × 1440, whose page
// faults a new array each pass would pay again).
void fold_totals(const RenderState& st, std::vector<PixelSums>& totals) {
  totals.resize(st.pixels.size());
  tbb::parallel_for(std::size_t(0), st.pixels.size(), [&](std::size_t i) { totals[i] = fold_blocks(st.pixels[i]); });
}

}  // namespace

double mean_spp(const RenderLayers& layers) {
  double total = 0;
  for (float n : layers.samples.data) total += n;
  return layers.samples.data.empty() ? 0.0 : total / double(layers.samples.data.size());
}

RenderLayers layers_from_state(const RenderState& st) {
  RenderLayers out = layers_from_blocks(st);
  out.spp_done = st.spp_done;
  out.sample_begin = st.sample_begin;
  out.interrupted = st.spp_done < st.sample_end - st.sample_begin;
  out.nonfinite_samples = st.nonfinite;
  return out;
}

namespace {

// The passes over [st.sample_begin, st.sample_end), from where the state is.
void run_passes(const PassContext& c, RenderState& st) {
  const int begin = st.sample_begin, end = st.sample_end, passes = plan_passes(st);
  std::vector<PixelSums> totals;  // adaptive sampling's judgement, between passes
  for (; st.passes_done < passes; ++st.passes_done) {
    const int s0 = plan_pass_start(st, st.passes_done), s1 = plan_pass_start(st, st.passes_done + 1);
    if (!run_pass(c, s0, s1, st.tiles_done, st.resumable)) break;  // stopped
    st.spp_done = s1 - begin;
    if (st.noise_target > 0) {
      fold_totals(st, totals);
      stop_converged(totals, st.width, st.height, st.noise_target, st.stopped);
    }
    if (c.progress) {
      std::lock_guard<std::mutex> lock(c.progress_mutex);
      c.progress({double(st.spp_done) / (end - begin), st.spp_done, mean_relative_noise(st)});
    }
  }
}

}  // namespace

RenderLayers render(const Camera& camera, const Integrator& integrator, const RenderSettings& settings,
                    const ProgressFn& progress, RenderState* state) {
  const auto start = std::chrono::steady_clock::now();
  const int w = camera.width, h = camera.height, spp = std::max(1, settings.spp);
  const int begin = settings.sample_begin, end = settings.sample_end < 0 ? spp : settings.sample_end;
  if (begin < 0 || end <= begin || end > spp)
    throw std::invalid_argument("render: the sample range is not within [0, spp)");
  if (!(settings.noise_target >= 0) || (settings.noise_target > 0 && (begin != 0 || end != spp)))
    throw std::invalid_argument("render: adaptive sampling renders whole images, with a noise target >= 0");
  RenderState local;
  RenderState& st = state ? *state : local;
  start_state(st, w, h, spp, begin, end, settings.noise_target);
  std::atomic<std::size_t> nonfinite{st.nonfinite};
  std::mutex progress_mutex;
  // Passes of samples over the whole image, so that progress can report samples per pixel done
  // and the noise reached: 8 passes (fewer when there are fewer samples; an adaptive render's are
  // shorter, render_state.h), area-weighted progress within.
  const int done = plan_pass_start(st, st.passes_done) - begin;
  std::atomic<long> area_done{long(w) * h * done};  // (a cancelled pass's tiles aside)
  const PassContext c{camera,
                      integrator,
                      settings,
                      progress,
                      spp,
                      begin,
                      camera.R_cam_from_world.row(2).transpose().cast<float>(),  // the optical axis
                      st.pixels,
                      st.stopped,
                      nonfinite,
                      area_done,
                      progress_mutex,
                      double(w) * h * (end - begin)};
  if (progress) progress({double(done) / (end - begin), done, -1.0});
  run_passes(c, st);
  st.nonfinite = nonfinite;
  RenderLayers out = layers_from_state(st);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace insitu
