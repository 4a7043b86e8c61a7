#include "relight/fit_resolution.h"

#include <algorithm>
#include <cmath>

#include "core/colour.h"
#include "light/texel_geometry.h"

namespace insitu {

namespace {

// The coarse index (of m) of full-resolution index i (of n): the coarse texel holding its centre.
int coarse_index(int i, int n, int m) { return std::min(m - 1, int((2 * std::int64_t(i) + 1) * m / (2 * n))); }

std::size_t coarse_id(int f, int i, int j, int n, int m) {
  return (std::size_t(f) * std::size_t(m) + std::size_t(coarse_index(j, n, m))) * std::size_t(m) +
         std::size_t(coarse_index(i, n, m));
}

}  // namespace

FitCubes shrink_for_fit(const CubeMap& radiance, const CubeMap& clipped, int max_face) {
  const int n = radiance.size(), m = std::min(n, std::max(1, max_face));
  if (m == n) return {radiance, clipped};
  const std::vector<double> omega = face_solid_angles(n);
  std::vector<Eigen::Array3d> sum(std::size_t(6) * m * m, Eigen::Array3d::Zero());
  std::vector<double> weight(sum.size(), 0.0);
  std::vector<Rgb> clip(sum.size(), Rgb::Zero());
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::size_t c = coarse_id(f, i, j, n, m);
        const double dw = omega[std::size_t(j) * std::size_t(n) + std::size_t(i)];
        sum[c] += dw * radiance.texel(f, i, j).cast<double>();
        weight[c] += dw;
        clip[c] = clip[c].cwiseMax(clipped.texel(f, i, j));
      }
  FitCubes out{CubeMap(m), CubeMap(m)};
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const std::size_t c = (std::size_t(f) * m + j) * m + i;
        out.radiance.set_texel(f, i, j, (sum[c] / std::max(1e-300, weight[c])).cast<float>());
        out.clipped.set_texel(f, i, j, clip[c]);
      }
  out.radiance.update_borders();
  out.clipped.update_borders();
  return out;
}

void map_to_full_resolution(InverseLightingResult& res, const CubeMap& radiance, const CubeMap& clipped) {
  const int n = radiance.size();
  if (res.parts.empty() || res.fit_face_size == n) return;
  const int m = res.fit_face_size;
  std::vector<int> part_of(std::size_t(6) * m * m, -1);
  for (std::size_t p = 0; p < res.parts.size(); ++p)
    for (const auto& t : res.parts[p].texels.texels)
      part_of[(std::size_t(t[0]) * m + std::size_t(t[2])) * m + std::size_t(t[1])] = int(p);
  std::vector<std::vector<std::array<int, 3>>> fine(res.parts.size());
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (const int p = part_of[coarse_id(f, i, j, n, m)]; p >= 0 && clipped.texel(f, i, j).maxCoeff() >= 0.5f)
          fine[std::size_t(p)].push_back({f, i, j});
  std::vector<std::vector<std::array<int, 3>>> by_source(res.sources.size());
  for (std::size_t p = 0; p < res.parts.size(); ++p) {
    PartFit& part = res.parts[p];
    const double coarse_power = part.texels.power;
    auto& src = by_source[std::size_t(part.source)];
    src.insert(src.end(), fine[p].begin(), fine[p].end());
    part.texels = clipped_source(std::move(fine[p]), radiance);
    // s_full = 1 + (s − 1) P_coarse / P_clipped: the same added power.
    part.scale = part.texels.power > 0 ? 1 + (part.scale - 1) * coarse_power / part.texels.power : 1.0;
  }
  res.clipped_power_share = 0;
  res.cube_power = cube_power(radiance);
  for (std::size_t k = 0; k < res.sources.size(); ++k) {
    SourceFit& s = res.sources[k];
    const double coarse_power = s.source.power;
    s.source = clipped_source(std::move(by_source[k]), radiance);
    const double ratio = s.source.power > 0 ? coarse_power / s.source.power : 1.0;
    s.scale = 1 + (s.scale - 1) * ratio;
    s.sigma *= ratio;
    res.clipped_power_share += res.cube_power > 0 ? s.source.power / res.cube_power : 0;
  }
}

}  // namespace insitu
