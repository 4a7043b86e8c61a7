// The room's light at a catalogue still's size (light/room_light.h): its memory and the cost of its
// queries. Six 12-megapixel shots give a 1024 face; with a window the light keeps three samplers
// (the whole cube, the walls and the outside), without one a single sampler.
//   build/bench/insitu_bench --benchmark_filter=RoomLight
// BM_RoomLightBuild/n/window: peak_mb (peak_memory.h) above the cube while it is built, and
// kept_mb, what the light holds once built (malloc's bytes in use, mallinfo2), also per texel.
// BM_RoomLightQuery/n/window: one next-event query as the path integrator makes it (a sample, then the pdf and the
// radiance along a second direction), at points spread through the room; the cube's texels are far more than the caches
// hold, so this is the cost of its memory layout.
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <cmath>
#include <memory>
#include <random>

#include "light/room_light.h"
#include "peak_memory.h"

namespace {
using namespace insitu;

// Walls of a smooth gradient, a bright sky and a sun through the window's directions, a lamp above.
CubeMap room_cube(int n) {
  CubeMap cube(n);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vec3f d = texel_direction(f, i, j, n);
        const float wall = 0.3f + 0.1f * d.x() + 0.05f * d.y();
        Rgb v(wall, 0.9f * wall, 0.8f * wall);
        if (d.z() < -0.6f && std::abs(d.y()) < 0.4f) v = Rgb(2.0f, 2.5f, 3.5f);  // the window's sky
        if (d.dot(Vec3f(0.2f, 0.3f, -1.0f).normalized()) > std::cos(0.01f)) v = Rgb(5e4f, 4.8e4f, 4.5e4f);
        if (d.y() > 0.995f) v = Rgb(300.0f, 250.0f, 180.0f);  // the lamp
        cube.set_texel(f, i, j, v);
      }
  cube.update_borders();
  return cube;
}

RoomBox room_box(bool window) {
  RoomBox box;
  box.min = Vec3f(-2.5f, 0.0f, -3.0f);
  box.max = Vec3f(2.5f, 2.6f, 3.0f);
  box.capture = Vec3f(-0.2f, 0.9f, -1.2f);
  if (window) box.openings.push_back({2, Vec3f(-1.0f, 0.8f, -3.0f), Vec3f(1.0f, 2.2f, -3.0f)});
  return box;
}

// malloc's bytes in use: its heap's and its mmap'ed blocks.
double allocated_mb() {
  const struct mallinfo2 m = mallinfo2();
  return double(m.uordblks + m.hblkhd) / (1024.0 * 1024.0);
}

void BM_RoomLightBuild(benchmark::State& state) {
  const int n = int(state.range(0));
  const CubeMap cube = room_cube(n);
  double peak_mb = 0, kept_mb = 0;
  for (auto _ : state) {
    bench::PeakMemory memory;
    const double before = allocated_mb();
    auto light = std::make_unique<RoomLight>(cube, room_box(state.range(1) != 0));
    benchmark::DoNotOptimize(light.get());
    peak_mb = memory.peak_mb();
    kept_mb = allocated_mb() - before;
  }
  state.counters["peak_mb"] = peak_mb;
  state.counters["kept_mb"] = kept_mb;
  state.counters["bytes_per_texel"] = kept_mb * 1024.0 * 1024.0 / (6.0 * n * n);
}
BENCHMARK(BM_RoomLightBuild)->Args({1024, 0})->Args({1024, 1})->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

void BM_RoomLightQuery(benchmark::State& state) {
  const int n = int(state.range(0));
  const RoomLight light(room_cube(n), room_box(state.range(1) != 0));
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0, 1);
  std::normal_distribution<float> g(0, 1);
  for (auto _ : state) {
    const Vec3f x(-2.4f + 4.8f * u(rng), 0.01f + 2.5f * u(rng), -2.9f + 5.8f * u(rng));
    const RoomSample s = light.sample(x, u(rng), u(rng), u(rng));
    const Vec3f d = Vec3f(g(rng), g(rng), g(rng)).normalized();
    benchmark::DoNotOptimize(s.pdf + light.pdf(x, d) + light.radiance(x, d)[0]);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RoomLightQuery)->Args({1024, 0})->Args({1024, 1});

}  // namespace
