// Writing and reading a part or checkpoint (render/checkpoint.h): the demo's state at 640×480
// after S samples of 16 (BM_StateFile/S: 4 is one block a pixel, as a finished power-of-two part
// has; 6 is two, 4 + 2, as a checkpoint between passes has), rendered once; the counters are its
// bytes per pixel on disk and per block. A 1920×1440 still has 9 times the pixels.
//   build/bench/insitu_bench --benchmark_filter=StateFile
#include <benchmark/benchmark.h>

#include <filesystem>

#include "render/checkpoint.h"
#include "scene/pipeline.h"

namespace {
using namespace insitu;

RenderState demo_state(int samples) {
  SceneSpec spec = parse_scene_file(std::string(INSITU_SOURCE_DIR) + "/scenes/demo/scene.json");
  spec.render.integrator = "path";
  spec.render.spp = 16;
  const LoadedScene scene = load_scene(spec);
  RenderState state;
  RenderControl control;
  control.state = &state, control.sample_end = samples;
  render_scene(scene, {}, control);
  return state;
}

void BM_StateFile(benchmark::State& state) {
  const RenderState st = demo_state(int(state.range(0)));
  const std::string path = (std::filesystem::temp_directory_path() / "insitu_bench.part").string();
  for (auto _ : state) {
    write_checkpoint(path, st, 1);
    benchmark::DoNotOptimize(read_state_file(path));
  }
  double blocks = 0;
  for (const PixelBlocks& p : st.pixels) blocks += double(p.size());
  const double bytes = double(std::filesystem::file_size(path)), pixels = double(st.pixels.size());
  state.counters["bytes/pixel"] = bytes / pixels;
  state.counters["bytes/block"] = bytes / blocks;
  state.counters["pixels/s"] = benchmark::Counter(pixels * double(state.iterations()), benchmark::Counter::kIsRate);
  std::filesystem::remove(path);
}
BENCHMARK(BM_StateFile)->Arg(4)->Arg(6)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
