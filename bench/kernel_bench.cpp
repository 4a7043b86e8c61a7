// The kernel against Embree (issue 16): rays per second of a `path` render of the demo, against a
// bare rtcIntersect1 / rtcOccluded1 loop over the very same rays (recorded by a RayLog during one
// render, replayed in each thread's order), each on 1 and on 2 threads.
//   build/bench/insitu_bench --benchmark_filter='Kernel|BareEmbree'
// The kernel's share of Embree's speed is rays/s of BM_KernelPath/T over that of BM_BareEmbree/T;
// the scaling is /2 over /1. Both exclude loading the scene; the render includes everything else
// (shading, light sampling, the catcher, accumulation, the composite).
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

#include "render/ray_log.h"
#include "scene/pipeline.h"

namespace {
using namespace insitu;

constexpr int kSpp = 16;
constexpr std::size_t kPiece = 4096;  // consecutive rays of one thread: a unit of the replay's work

struct DemoRays {
  LoadedScene scene;
  std::vector<std::vector<LoggedRay>> pieces;
  double count = 0, shadow = 0;
};

DemoRays record_demo_rays() {
  DemoRays d;
  SceneSpec spec = parse_scene_file(std::string(INSITU_SOURCE_DIR) + "/scenes/demo/scene.json");
  spec.render.integrator = "path";
  spec.render.spp = kSpp;
  d.scene = load_scene(spec);
  RayLog log;
  d.scene.objects->set_ray_log(&log);
  render_scene(d.scene);
  d.scene.objects->set_ray_log(nullptr);
  for (const std::vector<LoggedRay>& list : log.lists())
    for (std::size_t i = 0; i < list.size(); i += kPiece) {
      d.pieces.emplace_back(list.begin() + long(i), list.begin() + long(std::min(list.size(), i + kPiece)));
      for (const LoggedRay& r : d.pieces.back()) d.shadow += r.shadow ? 1 : 0;
    }
  d.count = double(log.size());
  return d;
}

const DemoRays& demo_rays() {
  static const DemoRays rays = record_demo_rays();
  return rays;
}

void set_counters(benchmark::State& state, const DemoRays& d) {
  const double n = d.count * double(state.iterations());
  state.counters["rays/s"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
  state.counters["rays"] = d.count;
  state.counters["shadow_share"] = d.shadow / d.count;
}

// The render, as `insitu render` runs it (load excluded).
void BM_KernelPath(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(state.range(0)));
  const DemoRays& d = demo_rays();
  for (auto _ : state) benchmark::DoNotOptimize(render_scene(d.scene));
  set_counters(state, d);
}
BENCHMARK(BM_KernelPath)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void trace_bare(RTCScene scene, const std::vector<LoggedRay>& rays) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (const LoggedRay& r : rays) {
    RTCRayHit rh;
    rh.ray.org_x = r.org[0], rh.ray.org_y = r.org[1], rh.ray.org_z = r.org[2];
    rh.ray.dir_x = r.dir[0], rh.ray.dir_y = r.dir[1], rh.ray.dir_z = r.dir[2];
    rh.ray.tnear = r.t_near, rh.ray.tfar = r.t_far, rh.ray.time = 0.0f;
    rh.ray.mask = 0xFFFFFFFFu, rh.ray.id = 0, rh.ray.flags = 0;
    if (r.shadow) {
      rtcOccluded1(scene, &context, &rh.ray);
      benchmark::DoNotOptimize(rh.ray.tfar);
    } else {
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &context, &rh);
      benchmark::DoNotOptimize(rh.hit.geomID);
    }
  }
}

// The same rays through Embree alone: no shading, no sampling, no bookkeeping.
void BM_BareEmbree(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(state.range(0)));
  const DemoRays& d = demo_rays();
  const RTCScene scene = d.scene.objects->rtc_scene();
  for (auto _ : state)
    tbb::parallel_for(std::size_t(0), d.pieces.size(), [&](std::size_t i) { trace_bare(scene, d.pieces[i]); });
  set_counters(state, d);
}
BENCHMARK(BM_BareEmbree)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Whether packets pay (issue 16, item 4): the demo's primary rays, 1 spp at pixel centres, one
// thread, through rtcIntersect1 one by one and through rtcIntersect8 in 4×2-pixel packets (the
// most coherent rays the renderer has). The gain a render could get is this speed-up applied to the
// primary rays' share of its Embree time, itself a share of the render (docs/performance.md).
std::vector<Ray> primary_rays(const LoadedScene& scene) {
  std::vector<Ray> rays;  // in 4×2 blocks, row-major within a block
  const int w = scene.camera.width, h = scene.camera.height;
  for (int y0 = 0; y0 + 2 <= h; y0 += 2)
    for (int x0 = 0; x0 + 4 <= w; x0 += 4)
      for (int k = 0; k < 8; ++k) rays.push_back(scene.camera.ray({x0 + k % 4 + 0.5, y0 + k / 4 + 0.5}));
  return rays;
}

void BM_BarePrimary1(benchmark::State& state) {
  const DemoRays& d = demo_rays();
  const std::vector<Ray> rays = primary_rays(d.scene);
  const RTCScene scene = d.scene.objects->rtc_scene();
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (auto _ : state)
    for (const Ray& r : rays) {
      RTCRayHit rh;
      rh.ray.org_x = r.origin.x(), rh.ray.org_y = r.origin.y(), rh.ray.org_z = r.origin.z();
      rh.ray.dir_x = r.dir.x(), rh.ray.dir_y = r.dir.y(), rh.ray.dir_z = r.dir.z();
      rh.ray.tnear = 0, rh.ray.tfar = std::numeric_limits<float>::infinity(), rh.ray.time = 0;
      rh.ray.mask = 0xFFFFFFFFu, rh.ray.id = 0, rh.ray.flags = 0;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &context, &rh);
      benchmark::DoNotOptimize(rh.hit.geomID);
    }
  state.counters["rays/s"] = benchmark::Counter(double(rays.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BarePrimary1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_BarePrimary8(benchmark::State& state) {
  const DemoRays& d = demo_rays();
  const std::vector<Ray> rays = primary_rays(d.scene);
  const RTCScene scene = d.scene.objects->rtc_scene();
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  const int valid[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
  for (auto _ : state)
    for (std::size_t b = 0; b < rays.size(); b += 8) {
      alignas(32) RTCRayHit8 rh;
      for (int k = 0; k < 8; ++k) {
        const Ray& r = rays[b + std::size_t(k)];
        rh.ray.org_x[k] = r.origin.x(), rh.ray.org_y[k] = r.origin.y(), rh.ray.org_z[k] = r.origin.z();
        rh.ray.dir_x[k] = r.dir.x(), rh.ray.dir_y[k] = r.dir.y(), rh.ray.dir_z[k] = r.dir.z();
        rh.ray.tnear[k] = 0, rh.ray.tfar[k] = std::numeric_limits<float>::infinity(), rh.ray.time[k] = 0;
        rh.ray.mask[k] = 0xFFFFFFFFu, rh.ray.id[k] = 0, rh.ray.flags[k] = 0;
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect8(valid, scene, &context, &rh);
      benchmark::DoNotOptimize(rh.hit.geomID[0]);
    }
  state.counters["rays/s"] = benchmark::Counter(double(rays.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BarePrimary8)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
