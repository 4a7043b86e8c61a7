// The kernel against Embree (issue 16): rays per second of a `path` render of the demo, against a
// bare rtcIntersect1 / rtcOccluded1 loop over the very same rays (recorded by a RayLog during one
// render, replayed in each thread's order), each on 1 and on 2 threads, on the demo and on the
// demo with its objects subdivided to furniture size (kHeavy).
//   build/bench/insitu_bench --benchmark_filter='Kernel|BareEmbree'
// The render's share of Embree's speed is rays/s of BM_KernelPath/T/L over that of
// BM_BareEmbree/T/L; the scaling is /2 over /1. Both exclude loading the scene; the render includes
// everything else (shading, light sampling, the catcher, accumulation, the composite).
// BM_KernelTrace/T/L replays the rays through insitu's tracing layer alone.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

#include "render/ray_log.h"
#include "scene/pipeline.h"
#include "subdivide.h"

namespace {
using namespace insitu;

constexpr int kSpp = 16;
constexpr std::size_t kPiece = 4096;  // consecutive rays of one thread: a unit of the replay's work

struct DemoRays {
  LoadedScene scene;
  std::vector<std::vector<LoggedRay>> pieces;
  double count = 0, shadow = 0, triangles = 0;
  Image composite;  // of the recording render (linear)
};

// The demo's objects, each triangle split into 4^levels by midpoint subdivision (subdivide.h).
void subdivide_objects(LoadedScene& scene, int levels) {
  std::vector<Mesh> meshes;
  for (const Mesh& mesh : scene.objects->meshes()) meshes.push_back(subdivide_midpoint(mesh, levels));
  scene.objects = std::make_unique<EmbreeScene>(std::move(meshes));
}

DemoRays record_demo_rays(int levels) {
  DemoRays d;
  SceneSpec spec = parse_scene_file(std::string(INSITU_SOURCE_DIR) + "/scenes/demo/scene.json");
  spec.render.integrator = "path";
  spec.render.spp = kSpp;
  d.scene = load_scene(spec);
  if (levels > 0) subdivide_objects(d.scene, levels);
  for (const Mesh& mesh : d.scene.objects->meshes()) d.triangles += double(mesh.triangles.size());
  RayLog log;
  d.scene.objects->set_ray_log(&log);
  d.composite = render_scene(d.scene).composite_linear;
  d.scene.objects->set_ray_log(nullptr);
  for (const std::vector<LoggedRay>& list : log.lists())
    for (std::size_t i = 0; i < list.size(); i += kPiece) {
      d.pieces.emplace_back(list.begin() + long(i), list.begin() + long(std::min(list.size(), i + kPiece)));
      for (const LoggedRay& r : d.pieces.back()) d.shadow += r.shadow ? 1 : 0;
    }
  d.count = double(log.size());
  return d;
}

// kHeavy: the demo's 2298 triangles subdivided 4 times, 588 288 triangles: a furniture model's size.
constexpr int kHeavy = 4;

const DemoRays& demo_rays(int levels = 0) {
  if (levels == kHeavy) {
    static const DemoRays heavy = record_demo_rays(kHeavy);
    return heavy;
  }
  static const DemoRays rays = record_demo_rays(0);
  return rays;
}

void set_counters(benchmark::State& state, const DemoRays& d) {
  const double n = d.count * double(state.iterations());
  state.counters["rays/s"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
  state.counters["rays"] = d.count;
  state.counters["shadow_share"] = d.shadow / d.count;
  state.counters["triangles"] = d.triangles;
}

// Σ|a − b| / Σ|b| over every pixel and channel: the subdivided demo renders the demo's image.
double relative_difference(const Image& a, const Image& b) {
  double diff = 0, sum = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i)
    diff += std::abs(double(a.data[i]) - double(b.data[i])), sum += std::abs(double(b.data[i]));
  return diff / sum;
}

// The render, as `insitu render` runs it (load excluded).
void BM_KernelPath(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(state.range(0)));
  const DemoRays& d = demo_rays(int(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(render_scene(d.scene));
  set_counters(state, d);
  if (state.range(1) > 0) state.counters["image_diff"] = relative_difference(d.composite, demo_rays(0).composite);
}
// Arguments: threads, subdivision levels (0: the demo; kHeavy: its objects at furniture size).
BENCHMARK(BM_KernelPath)->ArgsProduct({{1, 2}, {0, kHeavy}})->Unit(benchmark::kMillisecond)->UseRealTime();

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
  const DemoRays& d = demo_rays(int(state.range(1)));
  const RTCScene scene = d.scene.objects->rtc_scene();
  for (auto _ : state)
    tbb::parallel_for(std::size_t(0), d.pieces.size(), [&](std::size_t i) { trace_bare(scene, d.pieces[i]); });
  set_counters(state, d);
}
BENCHMARK(BM_BareEmbree)->ArgsProduct({{1, 2}, {0, kHeavy}})->Unit(benchmark::kMillisecond)->UseRealTime();

// The same rays through insitu's own tracing layer, what the integrators call: EmbreeScene's
// intersect() and transmittance(), and surface() at every hit (the shading point: barycentric position,
// normals, UV, material). Its rays/s over BM_BareEmbree's is the overhead of the layer itself.
void trace_insitu(const EmbreeScene& objects, const std::vector<LoggedRay>& rays) {
  for (const LoggedRay& r : rays) {
    const Ray ray{Vec3f(r.org[0], r.org[1], r.org[2]), Vec3f(r.dir[0], r.dir[1], r.dir[2])};
    if (r.shadow) {
      benchmark::DoNotOptimize(objects.transmittance(ray, r.t_near, r.t_far));
      continue;
    }
    const Hit hit = objects.intersect(ray, r.t_near, r.t_far);
    if (hit.valid()) {
      const SurfacePoint sp = objects.surface(ray, hit);
      benchmark::DoNotOptimize(sp);
    }
  }
}

void BM_KernelTrace(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(state.range(0)));
  const DemoRays& d = demo_rays(int(state.range(1)));
  for (auto _ : state)
    tbb::parallel_for(std::size_t(0), d.pieces.size(),
                      [&](std::size_t i) { trace_insitu(*d.scene.objects, d.pieces[i]); });
  set_counters(state, d);
}
BENCHMARK(BM_KernelTrace)->ArgsProduct({{1, 2}, {0, kHeavy}})->Unit(benchmark::kMillisecond)->UseRealTime();

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
  state.counters["rays/s"] =
      benchmark::Counter(double(rays.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
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
  state.counters["rays/s"] =
      benchmark::Counter(double(rays.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BarePrimary8)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
