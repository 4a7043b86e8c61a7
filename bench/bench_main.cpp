// Benchmarks of the foundation (Google Benchmark):
//   build/bench/insitu_bench                       all of them
//   build/bench/insitu_bench --benchmark_filter=Demo
// The figures quoted in README.md and the issue notes come from this program.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <filesystem>
#include <random>

#include "calib/calibration.h"
#include "core/sampler.h"
#include "light/cubemap.h"
#include "light/equirect.h"
#include "light/gaussian_irradiance.h"
#include "output/composite.h"
#include "output/denoise.h"
#include "render/mesh.h"
#include "scene/pipeline.h"

namespace {
using namespace insitu;

CubeMap random_cube(int n) {
  CubeMap cube(n);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0, 1);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) cube.set_texel(f, i, j, Rgb(u(rng), u(rng), u(rng)));
  cube.update_borders();
  return cube;
}

// Seamless bilinear cube lookups per second.
void BM_CubeLookup(benchmark::State& state) {
  const CubeMap cube = random_cube(int(state.range(0)));
  std::mt19937 rng(2);
  std::normal_distribution<float> g(0, 1);
  std::vector<Vec3f> dirs(4096);
  for (auto& d : dirs) d = Vec3f(g(rng), g(rng), g(rng));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(cube.lookup(dirs[i++ & 4095]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CubeLookup)->Arg(64)->Arg(512);

// Numbers per second of the sampler: a pixel's sample drawing 32 dimensions (16 pairs), as a path of
// a few bounces does; items are numbers.
void BM_SamplerNumbers(benchmark::State& state) {
  std::uint64_t sample = 0;
  for (auto _ : state) {
    Sampler sampler(7, 12345, sample++);
    float sum = 0;
    for (int d = 0; d < 32; ++d) sum += sampler.next();
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * 32);
}
BENCHMARK(BM_SamplerNumbers);

// The legacy per-face blur (kernel as wide as the face), per cube.
void BM_LegacyBlur(benchmark::State& state) {
  const CubeMap cube = random_cube(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(gaussian_blur_faces(cube));
}
BENCHMARK(BM_LegacyBlur)->Arg(64)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond);

// Loading a real mesh (validation pass + tinyobjloader + conversion).
void BM_LoadObj(benchmark::State& state) {
  const std::string path = std::string(INSITU_SHARED_DIR) + "/data/models/suzanne.obj";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("../shared/data/models/suzanne.obj is absent");
    return;
  }
  for (auto _ : state) {
    Warnings w;
    benchmark::DoNotOptimize(load_obj(path, w));
  }
}
BENCHMARK(BM_LoadObj)->Unit(benchmark::kMillisecond);

// The demo scene with the realtime integrator on T threads at S spp (BM_DemoRealtime/T/S): the
// preparation (the legacy blur) and the render, load excluded. At 1 spp it draws what the legacy
// renderer drew, one sample per pixel; 16 spp anti-alias. The ratio to BM_DemoPath64 is issue 16's
// "realtime ≥ 100× faster than path at 64 spp".
void BM_DemoRealtime(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(state.range(0)));
  SceneSpec spec = parse_scene_file(std::string(INSITU_SOURCE_DIR) + "/scenes/demo/scene.json");
  spec.render.integrator = "realtime";
  spec.render.spp = int(state.range(1));
  const LoadedScene scene = load_scene(spec);
  for (auto _ : state) benchmark::DoNotOptimize(render_scene(scene));
  state.counters["camera_samples/s"] = benchmark::Counter(
      double(scene.camera.width) * scene.camera.height * spec.render.spp * double(state.iterations()),
      benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DemoRealtime)->Args({1, 16})->Args({2, 16})->Args({2, 1})->Unit(benchmark::kMillisecond)->UseRealTime();

// The demo with `path` at 64 spp on 2 threads, preparation included: what BM_DemoRealtime/2/S is
// compared with.
void BM_DemoPath64(benchmark::State& state) {
  SceneSpec spec = parse_scene_file(std::string(INSITU_SOURCE_DIR) + "/scenes/demo/scene.json");
  spec.render.integrator = "path";
  spec.render.spp = 64;
  const LoadedScene scene = load_scene(spec);
  for (auto _ : state) benchmark::DoNotOptimize(render_scene(scene));
}
BENCHMARK(BM_DemoPath64)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

// The demo with `path` and its floor catcher, 16 spp, one thread: camera samples per second per
// core. BM_DemoPath/B/T: catcher_bounces B (5 the default, 1 Debevec's one-bounce catcher) and
// toward_objects T/10 (5: 0.5, the default; 0: cosine samples only).
void BM_DemoPath(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  SceneSpec spec = parse_scene_file(std::string(INSITU_SOURCE_DIR) + "/scenes/demo/scene.json");
  spec.render.integrator = "path";
  spec.render.spp = 16;
  spec.render.block.value["catcher_bounces"] = state.range(0);
  spec.render.block.value["toward_objects"] = double(state.range(1)) / 10;
  const LoadedScene scene = load_scene(spec);
  for (auto _ : state) benchmark::DoNotOptimize(render_scene(scene));
  state.counters["camera_samples/s"] = benchmark::Counter(
      double(scene.camera.width) * scene.camera.height * spec.render.spp * double(state.iterations()),
      benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DemoPath)->Args({5, 5})->Args({1, 5})->Args({5, 0})->Unit(benchmark::kMillisecond)->UseRealTime();

// The composite's denoiser (output/denoise.h) on the demo's 16-spp `path` render, T threads
// (BM_Denoise/T): the denoiser alone, the render done once before.
void BM_Denoise(benchmark::State& state) {
  SceneSpec spec = parse_scene_file(std::string(INSITU_SOURCE_DIR) + "/scenes/demo/scene.json");
  spec.render.integrator = "path";
  spec.render.spp = 16;
  const LoadedScene scene = load_scene(spec);
  const RenderResult r = render_scene(scene);
  const Image variance = composite_variance(scene.photo_linear, r.layers, spec.composite);
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(denoise_composite(scene.photo_linear, r.composite_linear, variance, r.layers));
  const Image touched = touched_mask(r.layers);
  state.counters["touched_pixels"] = double(std::count(touched.data.begin(), touched.data.end(), 1.0f));
}
BENCHMARK(BM_Denoise)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// A bare Embree rtcIntersect1 loop (through EmbreeScene::intersect) over the same primary rays,
// one thread: the floor under any integrator's cost per camera sample.
void BM_DemoPrimaryIntersect(benchmark::State& state) {
  SceneSpec spec = parse_scene_file(std::string(INSITU_SOURCE_DIR) + "/scenes/demo/scene.json");
  const LoadedScene scene = load_scene(spec);
  std::vector<Ray> rays;
  for (int y = 0; y < scene.camera.height; ++y)
    for (int x = 0; x < scene.camera.width; ++x) rays.push_back(scene.camera.ray({x + 0.5, y + 0.5}));
  for (auto _ : state)
    for (const Ray& r : rays) benchmark::DoNotOptimize(scene.objects->intersect(r));
  state.counters["rays/s"] =
      benchmark::Counter(double(rays.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DemoPrimaryIntersect)->Unit(benchmark::kMillisecond)->UseRealTime();

// Loading the demo scene: photo, six shots -> cube, three OBJ files, Embree build.
void BM_DemoLoad(benchmark::State& state) {
  const SceneSpec spec = parse_scene_file(std::string(INSITU_SOURCE_DIR) + "/scenes/demo/scene.json");
  for (auto _ : state) benchmark::DoNotOptimize(load_scene(spec));
}
BENCHMARK(BM_DemoLoad)->Unit(benchmark::kMillisecond);

// Calibration from n noisy non-coplanar points (σ = 1 px), model chosen automatically: starts
// (focal sweep + DLT), robust fit, outlier search, three models, F-tests and covariance.
void BM_Calibrate(benchmark::State& state) {
  const int n = int(state.range(0));
  const Camera truth = Camera::look_at({2, 1.6, 3}, {0, 0.8, 0}, {0, 1, 0}, 60, 1920, 1080);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g(0, 1);
  std::vector<ControlPoint> pts;
  for (int i = 0; i < n; ++i) {
    ControlPoint p;
    p.p_world = truth.unproject({1920 * (0.05 + 0.9 * u(rng)), 1080 * (0.05 + 0.9 * u(rng))}, 2 + 3 * u(rng));
    p.uv_px = truth.project(p.p_world) + Vec2d(g(rng), g(rng));
    p.name = std::to_string(i);
    pts.push_back(p);
  }
  for (auto _ : state) benchmark::DoNotOptimize(calibrate(pts, 1920, 1080));
}
BENCHMARK(BM_Calibrate)->Arg(6)->Arg(20)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
