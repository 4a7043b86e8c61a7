// The C API's overhead against the library calls the CLI makes (issue 15): the demo scene,
// loaded once, rendered and turned into its layers and report, by insitu_render and by
// render_scene + output_layers + render_report called directly. Both link libinsitu.so.
//
//   build/bench/insitu_api_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <insitu/insitu.h>

#include <string>

#include "scene/output_layers.h"
#include "scene/scene_file.h"

namespace {

const std::string kDemo = std::string(INSITU_SOURCE_DIR) + "/scenes/demo/scene.json";

// `integrator` at 16 spp: path is the final-still case, realtime the one where a fixed cost
// would show most.
void BM_CApiRender(benchmark::State& state, const char* integrator) {
  insitu_scene* scene = nullptr;
  if (insitu_scene_from_file(kDemo.c_str(), &scene) != INSITU_OK ||
      insitu_scene_set(scene, "render.integrator", ("\"" + std::string(integrator) + "\"").c_str()) != INSITU_OK ||
      insitu_scene_set(scene, "render.spp", "16") != INSITU_OK) {
    state.SkipWithError(insitu_last_error());
    return;
  }
  insitu_camera camera;
  insitu_scene_camera(scene, &camera);  // loads the scene, outside the loop
  for (auto _ : state) {
    insitu_result* result = nullptr;
    insitu_render(scene, nullptr, nullptr, &result);
    insitu_result_free(result);
  }
  insitu_scene_free(scene);
}

void BM_LibraryRender(benchmark::State& state, const char* integrator) {
  insitu::SceneSpec spec = insitu::parse_scene_file(kDemo);
  spec.render.integrator = integrator;
  spec.render.spp = 16;
  const insitu::LoadedScene scene = insitu::load_scene(spec);
  for (auto _ : state) {
    const insitu::RenderResult r = insitu::render_scene(scene);
    benchmark::DoNotOptimize(insitu::output_layers(scene, r));
    benchmark::DoNotOptimize(insitu::render_report(scene, r).dump(2));
  }
}

BENCHMARK_CAPTURE(BM_CApiRender, path, "path")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_LibraryRender, path, "path")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_CApiRender, realtime, "realtime")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_LibraryRender, realtime, "realtime")->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
