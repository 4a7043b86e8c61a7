// Registration of handheld shots (light/shot_registration.h): its time, and how well it recovers
// known misaims, on the shared HDRIs (../shared/data/hdri) seen as six ultra-wide (110°, 4:3)
// shots, each misaimed by σ = 2° per axis about a random axis (roll included), the misaims' mean taken
// out (the registration's prior fixes their common rotation at the nominal one).
//   build/bench/insitu_bench --benchmark_filter=Registration
// BM_RegisterShots/W: the time of register_shots on shots W pixels wide (4000: 12 megapixels).
// BM_RegistrationAccuracy/k: HDRI k; counters: the worst and mean angle between the recovered and
// the true aims, the shots registered, and the cube's mean relative error against the HDRI's own
// cube with the recovered aims and with the nominal ones.
// BM_PlumbLines/k: HDRI k, misaimed as a hand leaves it (the misaims' mean kept), registered, then
// levelled by its vertical lines (room_lines.h, LineAxes::vertical, as without a room box); counters:
// the mean tilt error (the angle by which a shot takes the world's up) and the mean angle error,
// each registered only and then levelled, and the shots levelled. Its time is the lines' alone.
// BM_PlumbLinesTime/W: that time on shots W pixels wide.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>

#include "light/equirect.h"
#include "light/room_lines.h"
#include "light/shot_registration.h"
#include "light/sixshot.h"
#include "../tests/handheld_shots.h"

namespace {
using namespace insitu;

const char* const kHdris[] = {"interior", "apartment", "city", "hall", "lab", "sunset", "warehouse"};

std::string hdri_path(const char* name) { return std::string(INSITU_SHARED_DIR) + "/data/hdri/" + name + ".exr"; }

void BM_RegisterShots(benchmark::State& state) {
  if (!std::filesystem::exists(hdri_path("interior"))) return state.SkipWithError("../shared/data is absent");
  const Image world = linearize(read_image_file(hdri_path("interior")));
  const ShotSet set =
      test::handheld_shots(world, test::misaims(1), 110, int(state.range(0)), int(state.range(0)) * 3 / 4);
  int registered = 0;
  for (auto _ : state) {
    const Registration r = register_shots(set);
    registered = 0;
    for (const ShotAim& a : r.shots) registered += a.registered;
  }
  state.counters["registered"] = registered;
}
BENCHMARK(BM_RegisterShots)->Arg(1200)->Arg(4000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RegistrationAccuracy(benchmark::State& state) {
  const char* name = kHdris[state.range(0)];
  if (!std::filesystem::exists(hdri_path(name))) return state.SkipWithError("../shared/data is absent");
  const Image world = linearize(read_image_file(hdri_path(name)));
  const std::array<Mat3d, 6> truth = test::misaims(unsigned(17 + state.range(0)));
  ShotSet set = test::handheld_shots(world, truth, 110, 1200, 900);
  Registration r;
  for (auto _ : state) r = register_shots(set);
  double worst = 0, mean = 0;
  int registered = 0;
  for (int s = 0; s < 6; ++s) {
    const double e = test::angle_deg(r.aim[std::size_t(s)], truth[std::size_t(s)]);
    worst = std::max(worst, e), mean += e / 6, registered += r.shots[std::size_t(s)].registered;
  }
  const int n = 128;
  const CubeMap reference = cube_from_equirect(world, n, 4);
  const double nominal = test::mean_relative_error(assemble_cube(set, n), reference);
  set.aim = r.aim;
  state.counters["worst_deg"] = worst;
  state.counters["mean_deg"] = mean;
  state.counters["registered"] = registered;
  state.counters["cube_err_nominal"] = nominal;
  state.counters["cube_err_registered"] = test::mean_relative_error(assemble_cube(set, n), reference);
  state.SetLabel(name);
}
BENCHMARK(BM_RegistrationAccuracy)->DenseRange(0, 6)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// The angle by which aim `a` takes the world's up where the shot's true aim is `truth`.
double tilt_deg(const Mat3d& a, const Mat3d& truth) {
  return rad_to_deg(std::acos(std::min(1.0, (a * truth.transpose())(1, 1))));
}

void BM_PlumbLines(benchmark::State& state) {
  const char* name = kHdris[state.range(0)];
  if (!std::filesystem::exists(hdri_path(name))) return state.SkipWithError("../shared/data is absent");
  const Image world = linearize(read_image_file(hdri_path(name)));
  const std::array<Mat3d, 6> truth = test::misaims(unsigned(17 + state.range(0)), false);
  ShotSet set = test::handheld_shots(world, truth, 110, 1200, 900);
  const Registration r = register_shots(set);
  set.aim = r.aim;
  LineAnchor a;
  for (auto _ : state) a = anchor_to_room_axes(set, r.group, LineAxes::vertical);
  double tilt_before = 0, tilt_after = 0, before = 0, after = 0;
  int levelled = 0;
  for (int s = 0; s < 6; ++s) {
    const auto i = std::size_t(s);
    const Mat3d levelled_aim = a.correction[i] * r.aim[i];
    tilt_before += tilt_deg(r.aim[i], truth[i]) / 6, tilt_after += tilt_deg(levelled_aim, truth[i]) / 6;
    before += test::angle_deg(r.aim[i], truth[i]) / 6, after += test::angle_deg(levelled_aim, truth[i]) / 6;
    levelled += a.anchored[i];
  }
  state.counters["tilt_registered_deg"] = tilt_before;
  state.counters["tilt_levelled_deg"] = tilt_after;
  state.counters["mean_registered_deg"] = before;
  state.counters["mean_levelled_deg"] = after;
  state.counters["levelled"] = levelled;
  state.SetLabel(name);
}
BENCHMARK(BM_PlumbLines)->DenseRange(0, 6)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PlumbLinesTime(benchmark::State& state) {
  if (!std::filesystem::exists(hdri_path("interior"))) return state.SkipWithError("../shared/data is absent");
  const Image world = linearize(read_image_file(hdri_path("interior")));
  const ShotSet set =
      test::handheld_shots(world, test::misaims(1, false), 110, int(state.range(0)), int(state.range(0)) * 3 / 4);
  for (auto _ : state) benchmark::DoNotOptimize(anchor_to_room_axes(set, {0, 0, 0, 0, 0, 0}, LineAxes::vertical));
}
BENCHMARK(BM_PlumbLinesTime)->Arg(1200)->Arg(4000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
