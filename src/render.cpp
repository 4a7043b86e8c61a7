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
        Rgb sum = Rgb::Zero(), with = Rgb::Zero(), without = Rgb::Zero();
        double coverage = 0;
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
        }
        out.objects.set_rgb(x, y, sum / float(spp));
        out.with_objects.set_rgb(x, y, with / float(spp));
        out.without_objects.set_rgb(x, y, without / float(spp));
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
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace insitu
