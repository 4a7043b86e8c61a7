// Loading an 8-bit panorama as the room's light (light/panorama.h, light/environment.h): peak
// memory and time for a 360° camera's JPEG, 5.7K (5760 × 2880, 16.6 megapixels) and 8K
// (7680 × 3840, 29.5 megapixels).
//   build/bench/insitu_bench --benchmark_filter=LoadPanorama
// The panorama is a room's walls (a smooth gradient) with a clipped ceiling lamp; the cube is the
// 8-bit panorama's at most 1024 a face, with its clipped cube. Counters: peak_mb (peak_memory.h),
// megapixels and the face.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "core/colour.h"
#include "core/image.h"
#include "light/environment.h"
#include "light/equirect.h"
#include "peak_memory.h"

namespace {
using namespace insitu;

std::string write_panorama(int width) {
  const int height = width / 2;
  Image img(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Vec3f d = equirect_to_direction((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height));
      const float wall = 0.35f + 0.2f * d.x() + 0.1f * d.y();
      const Rgb v = d.dot(Vec3f(0.1f, 1, 0.05f).normalized()) > std::cos(0.15f) ? Rgb(1, 1, 1) : Rgb(wall, wall, wall);
      img.set_rgb(x, y, v.unaryExpr([](float l) { return linear_to_srgb(std::min(l, 1.0f)); }));
    }
  const std::string path =
      (std::filesystem::temp_directory_path() / ("insitu_bench_pano_" + std::to_string(width) + ".jpg")).string();
  write_image(path, img);
  return path;
}

void BM_LoadPanorama(benchmark::State& state) {
  const int width = int(state.range(0));
  EnvironmentSpec spec;
  spec.image = write_panorama(width);
  spec.exposure = EnvironmentSpec::Exposure::kFactor;
  double peak_mb = 0;
  int face = 0;
  for (auto _ : state) {
    const bench::PeakMemory memory;
    Warnings warnings;
    EnvironmentInfo info;
    const CubeMap cube = load_environment(spec, warnings, &info);
    face = cube.size();
    peak_mb = std::max(peak_mb, memory.peak_mb());
  }
  std::filesystem::remove(spec.image);
  state.counters["peak_mb"] = peak_mb;
  state.counters["megapixels"] = double(width) * (width / 2) / 1e6;
  state.counters["face"] = face;
}
BENCHMARK(BM_LoadPanorama)->Arg(5760)->Arg(7680)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
