#include "light/irradiance_report.h"

#include <tbb/parallel_for.h>

#include <chrono>

#include "core/sampler.h"

namespace insitu {

std::vector<Vec3d> fibonacci_sphere(int count) {
  // z uniform in (−1, 1), azimuth advancing by the golden angle: equal-area points.
  std::vector<Vec3d> out;
  const double golden = kPi * (3 - std::sqrt(5.0));
  for (int k = 0; k < count; ++k) {
    const double z = 1 - (2.0 * k + 1) / count, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = golden * k;
    out.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  return out;
}

IrradianceReport irradiance_report(const CubeMap& radiance, int count, int exact_size) {
  using clock = std::chrono::steady_clock;
  IrradianceReport rep;
  rep.face_size = radiance.size();
  std::vector<Vec3d> normals = fibonacci_sphere(count);
  // The normal facing the brightest texel.
  float best = -1;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < radiance.size(); ++j)
      for (int i = 0; i < radiance.size(); ++i)
        if (luminance(radiance.texel(f, i, j)) > best) {
          best = luminance(radiance.texel(f, i, j));
          rep.brightest_direction = texel_direction(f, i, j, radiance.size()).cast<double>();
        }
  normals.push_back(rep.brightest_direction);
  rep.normals = int(normals.size());

  const auto t0 = clock::now();
  std::vector<float> ref(normals.size());
  tbb::parallel_for(std::size_t(0), normals.size(),
                    [&](std::size_t k) { ref[k] = luminance(irradiance_reference(radiance, normals[k])); });
  rep.reference_ms_per_normal =
      std::chrono::duration<double, std::milli>(clock::now() - t0).count() / double(normals.size());
  double mean_E = 0;
  for (std::size_t k = 0; k + 1 < normals.size(); ++k) mean_E += ref[k] / double(normals.size() - 1);

  std::vector<Vec3f> random_dirs(4096);
  for (std::size_t k = 0; k < random_dirs.size(); ++k) {
    Sampler s(7, k, 0);
    const float z = 1 - 2 * s.next(), phi = 2 * kPiF * s.next(), r = std::sqrt(std::max(0.0f, 1 - z * z));
    random_dirs[k] = Vec3f(r * std::cos(phi), r * std::sin(phi), z);
  }
  for (IrradianceMode mode : directional_irradiance_modes()) {
    ModeReport m;
    m.mode = mode;
    const auto p0 = clock::now();
    const auto field = make_irradiance(mode, radiance, exact_size);
    m.precompute_ms = std::chrono::duration<double, std::milli>(clock::now() - p0).count();
    const int lookups = 1000000;
    Rgb sink = Rgb::Zero();
    const auto l0 = clock::now();
    for (int k = 0; k < lookups; ++k) sink += field->irradiance(random_dirs[std::size_t(k) & 4095]);
    m.lookup_ns = std::chrono::duration<double, std::nano>(clock::now() - l0).count() / lookups;
    if (!sink.allFinite()) m.lookup_ns = -1;  // keeps the loop from being optimized away
    for (std::size_t k = 0; k < normals.size(); ++k) {
      const double e = luminance(field->irradiance(normals[k].cast<float>()));
      const double rel = std::abs(e - ref[k]) / std::max(double(ref[k]), 1e-3 * mean_E);
      if (k + 1 == normals.size())
        m.brightest_rel_error = rel;
      else {
        m.mean_rel_error += rel / double(normals.size() - 1);
        m.max_rel_error = std::max(m.max_rel_error, rel);
      }
    }
    rep.modes.push_back(m);
  }
  return rep;
}

}  // namespace insitu
