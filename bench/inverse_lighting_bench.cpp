// Inverse lighting's peak memory and time at a catalogue still's size (relight/fit_resolution.h):
// six 12-megapixel shots give a 1024 face; the photo is 1920 × 1440.
//   build/bench/insitu_bench --benchmark_filter=InverseLighting
// BM_InverseLighting/n: a 5 × 2.6 × 6 m room box with a window (the sky at 1, the sun at 300) and
// a ceiling lamp (25), clipped at 0.5 as an 8-bit shot clips, and grainy: 11 % of the ceiling's
// texels within 35° of the lamp clipped at random (high-ISO noise at the clip level). Counters:
// peak_mb, the resident memory's peak above what it was before the fit (Linux's VmHWM, reset
// through /proc/self/clear_refs after glibc's malloc_trim returned the setup's free memory), and
// the fit's parts, pixels and face.
// BM_UnseenOutside/n: the fit of the light through the window that the capture point saw as wall
// (relight/unseen_outside.h) on the same room and photo, after the clipped light's: its own time
// and peak memory, and f.
#include <benchmark/benchmark.h>

#include <cmath>
#include <fstream>
#include <random>
#include <string>

#include "peak_memory.h"
#include "core/camera.h"
#include "core/colour.h"
#include "core/image.h"
#include "light/plane_irradiance.h"
#include "relight/inverse_lighting.h"
#include "relight/photo_fill.h"
#include "relight/unseen_outside.h"

namespace {
using namespace insitu;

const RoomBox kBox{Vec3f(-2.5f, 0, -3),
                   Vec3f(2.5f, 2.6f, 3),
                   Vec3f(0, 1.2f, 0),
                   {RoomOpening{0, Vec3f(-2.5f, 0.9f, -2.2f), Vec3f(-2.5f, 2.1f, -0.6f)}},
                   std::nullopt};

// The room's true radiance along d from the capture point (texels of a face of n), and with the
// grain: 11 % of the ceiling's texels near the lamp at the clip level.
float true_radiance(const Vec3f& d, int n) {
  const Vec3f lamp = Vec3f(0.1f, 1, 0.05f).normalized(), sun = Vec3f(-1, 0.45f, 0.25f).normalized();
  const Vec3f hit = kBox.capture + (kBox.min.x() - kBox.capture.x()) / std::min(-1e-6f, d.x()) * d;
  const bool window = d.x() < 0 && hit.y() > 0.9f && hit.y() < 2.1f && hit.z() > -2.2f && hit.z() < -0.6f;
  float v = window ? (d.dot(sun) > std::cos(deg_to_rad(0.5f) + 1.5f / float(n)) ? 300.0f : 1.0f) : 0.2f;
  return d.dot(lamp) > std::cos(0.12f) ? 25.0f : v;
}

struct Shots {
  CubeMap radiance, clipped;
};

Shots grainy_shots(int n) {
  Shots r{CubeMap(n), CubeMap(n)};
  const Vec3f lamp = Vec3f(0.1f, 1, 0.05f).normalized();
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0, 1);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vec3f d = texel_direction(f, i, j, n);
        float v = true_radiance(d, n);
        if (f == kPosY && d.dot(lamp) > std::cos(deg_to_rad(35.0f)) && u(rng) < 0.11f) v = std::max(v, 0.5f);
        r.radiance.set_texel(f, i, j, Rgb::Constant(std::min(v, 0.5f)));
        r.clipped.set_texel(f, i, j, Rgb::Constant(v >= 0.5f ? 1.0f : 0.0f));
      }
  r.radiance.update_borders();
  r.clipped.update_borders();
  return r;
}

// The photo of the empty room, ρ = 0.5 everywhere: P = ρ/π E of the true light (a 64 face) at the
// box's face each pixel sees, 64 samples, at 240 × 180 and enlarged to the camera's size.
Image photo_of(const Camera& camera) {
  CubeMap truth(64);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i)
        truth.set_texel(f, i, j, Rgb::Constant(true_radiance(texel_direction(f, i, j, 64), 64)));
  truth.update_borders();
  const RoomLight light(truth, kBox);
  const int w = 240, h = 180;
  Image small(w, h, 3, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Ray ray = camera.ray(Vec2d((x + 0.5) * camera.width / w, (y + 0.5) * camera.height / h));
      float t = 0;
      int axis = 0;
      if (!light.exit(ray.origin, ray.dir, &t, &axis)) continue;
      Vec3f normal = Vec3f::Zero();
      normal[axis] = ray.dir[axis] > 0 ? -1.0f : 1.0f;
      const Vec3f p = ray.origin + t * ray.dir + 1e-4f * normal;
      small.set_rgb(x, y, 0.5f / kPiF * PlaneIrradiance::estimate(light, p, normal, 64, std::uint64_t(y * w + x)));
    }
  return resize(small, camera.width, camera.height);
}

// The fit's input at a catalogue still's size (the cubes and images it points to held by the caller).
struct Still {
  explicit Still(int n)
      : shots(grainy_shots(n)),
        camera(Camera::look_at(Vec3d(1.7, 1.45, 2.5), Vec3d(-0.2, 0.45, -1.2), Vec3d(0, 1, 0), 62, 1920, 1440)),
        photo(photo_of(camera)),
        photo_clipped(1920, 1440, 1, 0.0f) {
    in.radiance = &shots.radiance, in.clipped = &shots.clipped, in.room = kBox, in.camera = &camera;
    in.photo_linear = &photo, in.photo_clipped = &photo_clipped;
    in.planes.push_back({Vec3f::Zero(), Vec3f(0, 1, 0), std::nullopt, std::nullopt});
  }
  Shots shots;
  Camera camera;
  Image photo, photo_clipped;
  InverseLightingInput in;
};

// fit() in the benchmark's loop, its peak memory as the counter peak_mb; returns its last result.
template <typename Fit>
auto timed(benchmark::State& state, const Fit& fit) {
  decltype(fit()) r;
  double peak_mb = 0;
  for (auto _ : state) {
    const bench::PeakMemory memory;
    r = fit();
    peak_mb = std::max(peak_mb, memory.peak_mb());
  }
  state.counters["peak_mb"] = peak_mb;
  return r;
}

void BM_InverseLighting(benchmark::State& state) {
  const Still still(int(state.range(0)));
  const InverseLightingInput& in = still.in;
  const InverseLightingResult r = timed(state, [&] { return recover_clipped_sources(in); });
  state.counters["parts"] = double(r.parts.size());
  state.counters["pixels"] = r.pixels;
  state.counters["fit_face"] = r.fit_face_size;
  state.SetLabel(r.status);
}
BENCHMARK(BM_InverseLighting)->Arg(256)->Arg(1024)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

void BM_UnseenOutside(benchmark::State& state) {
  const Still still(int(state.range(0)));
  const CubeMap completed = recover_clipped_sources(still.in).apply(still.shots.radiance);
  InverseLightingInput in = still.in;
  in.radiance = &completed;
  const UnseenOutsideFit r = timed(state, [&] { return fit_unseen_outside(in); });
  state.counters["f"] = r.scale;
  state.counters["pixels"] = r.pixels;
  state.SetLabel(r.status);
}
BENCHMARK(BM_UnseenOutside)->Arg(1024)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

void BM_PhotoFill(benchmark::State& state) {
  const Still still(int(state.range(0)));
  const int n = still.shots.radiance.size();
  const double half_w = std::tan(deg_to_rad(35.0)), half_h = 0.75 * half_w;
  std::vector<bool> covered(std::size_t(6) * std::size_t(n) * std::size_t(n));
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        covered[(std::size_t(f) * std::size_t(n) + std::size_t(j)) * std::size_t(n) + std::size_t(i)] =
            std::abs(2 * (i + 0.5) / n - 1) < half_w && std::abs(2 * (j + 0.5) / n - 1) < half_h;
  PhotoFill r;
  double peak_mb = 0;
  for (auto _ : state) {
    state.PauseTiming();
    CubeMap radiance = still.shots.radiance;
    state.ResumeTiming();
    const bench::PeakMemory memory;
    r = fill_from_photo(radiance, covered, &still.shots.clipped, kBox, still.camera, still.photo, still.photo_clipped);
    peak_mb = std::max(peak_mb, memory.peak_mb());
  }
  state.counters["peak_mb"] = peak_mb;
  state.counters["uncovered"] = double(r.uncovered);
  state.counters["from_photo"] = double(r.from_photo);
  state.counters["level"] = r.level;
}
BENCHMARK(BM_PhotoFill)->Arg(256)->Arg(1024)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
