#include "render.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <mutex>

namespace insitu {

RenderLayers render(const Camera& camera, const Integrator& integrator, const RenderSettings& settings,
                    const ProgressFn& progress) {
  const auto start = std::chrono::steady_clock::now();
  const int w = camera.width, h = camera.height, spp = std::max(1, settings.spp);
  RenderLayers out;
  out.objects = Image(w, h, 3);
  out.alpha = Image(w, h, 1);
  out.with_objects = Image(w, h, 3);
  out.without_objects = Image(w, h, 3);
  out.normal = Image(w, h, 3);
  out.albedo = Image(w, h, 3);
  out.depth = Image(w, h, 1);
  out.samples = Image(w, h, 1, float(spp));
  out.variance = Image(w, h, 1);
  int grid = int(std::lround(std::sqrt(double(spp))));
  if (grid * grid != spp) grid = 0;  // not a perfect square: plain jitter
  std::atomic<std::size_t> nonfinite{0};
  std::atomic<long> rows_done{0};
  std::mutex progress_mutex;
  constexpr int kTile = 16;
  if (progress) progress(0.0);  // the loop starts now (integrators may have precomputed before)

  tbb::parallel_for(tbb::blocked_range2d<int>(0, h, kTile, 0, w, kTile), [&](const tbb::blocked_range2d<int>& r) {
    std::size_t local_nonfinite = 0;
    for (int y = r.rows().begin(); y < r.rows().end(); ++y)
      for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
        const std::uint64_t pixel = std::uint64_t(y) * std::uint64_t(w) + std::uint64_t(x);
        Rgb sum = Rgb::Zero(), with = Rgb::Zero(), without = Rgb::Zero(), albedo = Rgb::Zero();
        Vec3f normal = Vec3f::Zero();
        double coverage = 0, depth = 0, y_sum = 0, y_sum2 = 0;
        int met = 0;
        for (int s = 0; s < spp; ++s) {
          Sampler sampler(settings.seed, pixel, std::uint64_t(s));
          float jx = sampler.next(), jy = sampler.next();
          if (grid > 0) {
            jx = (float(s % grid) + jx) / float(grid);
            jy = (float(s / grid) + jy) / float(grid);
          }
          const CameraSample cs = integrator.sample(camera.ray({double(x) + jx, double(y) + jy}), sampler);
          if (!cs.radiance.allFinite() || !std::isfinite(cs.coverage) || !cs.with_objects.allFinite() ||
              !cs.without_objects.allFinite()) {
            ++local_nonfinite;
            continue;
          }
          sum += cs.radiance * cs.coverage;
          coverage += cs.coverage;
          with += cs.with_objects;
          without += cs.without_objects;
          const double lum = luminance(Rgb(cs.radiance * cs.coverage + cs.with_objects - cs.without_objects));
          y_sum += lum;
          y_sum2 += lum * lum;
          if (cs.depth > 0) {
            ++met;
            normal += cs.normal;
            albedo += cs.albedo;
            depth += cs.depth;
          }
        }
        out.objects.set_rgb(x, y, sum / float(spp));
        out.with_objects.set_rgb(x, y, with / float(spp));
        out.without_objects.set_rgb(x, y, without / float(spp));
        if (met > 0) {
          out.normal.set_rgb(x, y, Rgb(normal.array() / float(met)));
          out.albedo.set_rgb(x, y, albedo / float(met));
          *out.depth.at(x, y) = float(depth / met);
        }
        // Variance of the mean: (Σy² − (Σy)²/n) / (n (n − 1)).
        if (spp > 1) *out.variance.at(x, y) = float(std::max(0.0, (y_sum2 - y_sum * y_sum / spp) / (double(spp) * (spp - 1))));
        *out.alpha.at(x, y) = float(coverage / spp);
      }
    nonfinite += local_nonfinite;
    if (progress) {
      // Tiles are 16 rows high and as wide as kTile; count area done.
      const long area = long(r.rows().size()) * long(r.cols().size());
      const long done = rows_done += area;
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress(double(done) / (double(w) * h));
    }
  });
  out.nonfinite_samples = nonfinite;
  // The noise a person would see: over pixels the render changed, √variance relative to the change.
  double noise = 0;
  long changed = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float v = *out.variance.at(x, y);
      if (v <= 0) continue;
      const double value = std::abs(luminance(Rgb(out.objects.rgb(x, y) + out.with_objects.rgb(x, y) - out.without_objects.rgb(x, y)))) +
                           luminance(out.without_objects.rgb(x, y));
      if (value <= 0) continue;
      noise += std::sqrt(v) / value;
      ++changed;
    }
  out.mean_relative_noise = changed > 0 ? noise / double(changed) : 0.0;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace insitu
