#include "render/render.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <mutex>

namespace insitu {

namespace {

// What a pixel has gathered so far. Samples are added in index order, pass after pass, so the
// sums are the same whatever the passes and the threads.
struct PixelSums {
  Rgb objects = Rgb::Zero(), with = Rgb::Zero(), without = Rgb::Zero(), albedo = Rgb::Zero();
  Vec3f normal = Vec3f::Zero();
  double coverage = 0, depth = 0, y = 0, y2 = 0;
  // The catcher's luminance with (w) and without (n) the objects: sums of w, n, w², n², w·n over
  // all samples, and how many samples saw the catcher, for the composite's choice of estimator.
  double w = 0, n = 0, w2 = 0, n2 = 0, wn = 0;
  int met = 0, catcher = 0;
};

// Variance of the ratio of means R = w̄/n̄ by the delta method, with the correlation of w and n
// (Cochran 1977, §6.3): Var(R) ≈ Σ(wᵢ − R nᵢ)² / (k (k − 1) n̄²) over k samples.
double ratio_variance(const PixelSums& p, int k) {
  if (k < 2 || !(p.n > 0)) return 0.0;
  const double R = p.w / p.n, n_mean = p.n / k;
  const double d2 = std::max(0.0, p.w2 - 2 * R * p.wn + R * R * p.n2);
  return d2 / (double(k) * (k - 1) * n_mean * n_mean);
}

// Variance of the mean of w − n: (Σ(w − n)² − (Σ(w − n))²/k) / (k (k − 1)).
double difference_variance(const PixelSums& p, int k) {
  if (k < 2) return 0.0;
  const double s = p.w - p.n, s2 = p.w2 - 2 * p.wn + p.n2;
  return std::max(0.0, (s2 - s * s / k) / (double(k) * (k - 1)));
}

// Variance of the mean after n samples: (Σy² − (Σy)²/n) / (n (n − 1)).
double variance_of_mean(const PixelSums& p, int n) {
  return n > 1 ? std::max(0.0, (p.y2 - p.y * p.y / n) / (double(n) * (n - 1))) : 0.0;
}

// Mean over pixels the render changed (an object covers them or the catcher's estimates differ)
// of √variance relative to the pixel's value. Changed pixels of variance 0 count as 0, so that the
// set of pixels, and with it the figure, does not jump from pass to pass.
double mean_relative_noise(const std::vector<PixelSums>& sums, int n) {
  double noise = 0;
  long changed = 0;
  for (const PixelSums& p : sums) {
    if (p.coverage == 0 && p.w == p.n) continue;
    const double v = variance_of_mean(p, n);
    const double value = (std::abs(luminance(Rgb(p.objects + p.with - p.without))) + luminance(p.without)) / double(n);
    if (value <= 0) continue;
    noise += std::sqrt(v) / value;
    ++changed;
  }
  return changed > 0 ? noise / double(changed) : 0.0;
}

// The key of a pixel's order of strata.
std::uint32_t stratum_key(std::uint64_t pixel) {
  return std::uint32_t(hash4(0x5354524154ull, pixel, 0, 0) >> 32);  // "STRAT"
}

// Sample s of pixel (x, y): a jittered position, in stratum permute(s) of a grid × grid pixel
// when spp is a perfect square (grid > 0). Strata come in a per-pixel random order, so that every
// pass's prefix of samples covers the pixel evenly (row by row, the first passes would see only
// its top). Draws the sampler's first two numbers.
Ray jittered_ray(const Camera& camera, int x, int y, std::uint64_t pixel, int s, int spp, int grid, Sampler& sampler) {
  float jx = sampler.next(), jy = sampler.next();
  if (grid > 0) {
    const int stratum = int(permute(std::uint32_t(s), std::uint32_t(spp), stratum_key(pixel)));
    jx = (float(stratum % grid) + jx) / float(grid);
    jy = (float(stratum / grid) + jy) / float(grid);
  }
  return camera.ray({double(x) + jx, double(y) + jy});
}

// Adds one camera sample to its pixel; a non-finite one is refused (false) and added nowhere.
// depth.Z is camera-space z: the distance t along the unit ray times d · (optical axis).
bool accumulate(PixelSums& p, const CameraSample& cs, const Ray& ray, const Vec3f& axis_world) {
  if (!cs.radiance.allFinite() || !std::isfinite(cs.coverage) || !cs.with_objects.allFinite() ||
      !cs.without_objects.allFinite())
    return false;
  p.objects += cs.radiance * cs.coverage;
  p.coverage += cs.coverage;
  p.with += cs.with_objects;
  p.without += cs.without_objects;
  const double lum = luminance(Rgb(cs.radiance * cs.coverage + cs.with_objects - cs.without_objects));
  p.y += lum;
  p.y2 += lum * lum;
  const double wy = luminance(cs.with_objects), ny = luminance(cs.without_objects);
  p.w += wy, p.n += ny, p.w2 += wy * wy, p.n2 += ny * ny, p.wn += wy * ny;
  p.catcher += (wy != 0 || ny != 0);
  if (cs.depth > 0) {
    ++p.met;
    p.normal += cs.normal;
    p.albedo += cs.albedo;
    p.depth += double(cs.depth) * double(ray.dir.dot(axis_world));
  }
  return true;
}

// The layers: means over the spp samples (normal, albedo and depth over those that met something).
RenderLayers layers_from_sums(const std::vector<PixelSums>& sums, int w, int h, int spp) {
  RenderLayers out;
  out.objects = Image(w, h, 3);
  out.alpha = Image(w, h, 1);
  out.with_objects = Image(w, h, 3);
  out.without_objects = Image(w, h, 3);
  out.normal = Image(w, h, 3);
  out.albedo = Image(w, h, 3);
  out.depth = Image(w, h, 1, kNoHitDepth);
  out.samples = Image(w, h, 1, float(spp));
  out.variance = Image(w, h, 1);
  out.ratio_variance = Image(w, h, 1);
  out.difference_variance = Image(w, h, 1);
  out.catcher_samples = Image(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const PixelSums& p = sums[std::size_t(y) * w + x];
      out.objects.set_rgb(x, y, p.objects / float(spp));
      *out.alpha.at(x, y) = float(p.coverage / spp);
      out.with_objects.set_rgb(x, y, p.with / float(spp));
      out.without_objects.set_rgb(x, y, p.without / float(spp));
      if (p.met > 0) {
        out.normal.set_rgb(x, y, Rgb(p.normal.array() / float(p.met)));
        out.albedo.set_rgb(x, y, p.albedo / float(p.met));
        *out.depth.at(x, y) = float(p.depth / p.met);
      }
      *out.variance.at(x, y) = float(variance_of_mean(p, spp));
      *out.ratio_variance.at(x, y) = float(ratio_variance(p, spp));
      *out.difference_variance.at(x, y) = float(difference_variance(p, spp));
      *out.catcher_samples.at(x, y) = float(p.catcher);
    }
  out.mean_relative_noise = mean_relative_noise(sums, spp);
  return out;
}

}  // namespace

RenderLayers render(const Camera& camera, const Integrator& integrator, const RenderSettings& settings,
                    const ProgressFn& progress) {
  const auto start = std::chrono::steady_clock::now();
  const int w = camera.width, h = camera.height, spp = std::max(1, settings.spp);
  const Vec3f axis_world = camera.R_cam_from_world.row(2).transpose().cast<float>();  // the optical axis
  int grid = int(std::lround(std::sqrt(double(spp))));
  if (grid * grid != spp) grid = 0;  // not a perfect square: plain jitter
  std::vector<PixelSums> sums(std::size_t(w) * h);
  std::atomic<std::size_t> nonfinite{0};
  std::mutex progress_mutex;
  constexpr int kTile = 16;
  // Passes of samples over the whole image, so that progress can report samples per pixel done
  // and the noise reached: 8 passes (fewer when spp is smaller), area-weighted progress within.
  const int passes = std::min(spp, 8);
  if (progress) progress({0.0, 0, -1.0});  // the loop starts now (integrators may have precomputed before)
  std::atomic<long> area_done{0};
  const double total_work = double(w) * h * spp;

  for (int pass = 0; pass < passes; ++pass) {
    const int s0 = int(std::int64_t(spp) * pass / passes), s1 = int(std::int64_t(spp) * (pass + 1) / passes);
    tbb::parallel_for(tbb::blocked_range2d<int>(0, h, kTile, 0, w, kTile), [&](const tbb::blocked_range2d<int>& r) {
      std::size_t local_nonfinite = 0;
      for (int y = r.rows().begin(); y < r.rows().end(); ++y)
        for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
          const std::uint64_t pixel = std::uint64_t(y) * std::uint64_t(w) + std::uint64_t(x);
          for (int s = s0; s < s1; ++s) {
            Sampler sampler(settings.seed, pixel, std::uint64_t(s));
            const Ray ray = jittered_ray(camera, x, y, pixel, s, spp, grid, sampler);
            if (!accumulate(sums[pixel], integrator.sample(ray, sampler), ray, axis_world)) ++local_nonfinite;
          }
        }
      nonfinite += local_nonfinite;
      if (progress) {
        const long done = area_done += long(r.rows().size()) * long(r.cols().size()) * (s1 - s0);
        std::lock_guard<std::mutex> lock(progress_mutex);
        progress({double(done) / total_work, s0, -1.0});
      }
    });
    if (progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      progress({double(s1) / spp, s1, mean_relative_noise(sums, s1)});
    }
  }
  RenderLayers out = layers_from_sums(sums, w, h, spp);
  out.nonfinite_samples = nonfinite;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace insitu
