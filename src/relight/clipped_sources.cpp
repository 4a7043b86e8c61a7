#include "relight/clipped_sources.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <opencv2/imgproc.hpp>

#include "core/colour.h"
#include "light/texel_geometry.h"

namespace insitu {

namespace {

// The texel one step (di, dj) from (f, i, j), across a face edge through the direction there.
std::array<int, 3> neighbour(int f, int i, int j, int di, int dj, int n) {
  const int ni = i + di, nj = j + dj;
  if (ni >= 0 && ni < n && nj >= 0 && nj < n) return {f, ni, nj};
  const FaceCoord c =
      direction_to_face(face_to_direction(f, (float(ni) + 0.5f) / float(n), (float(nj) + 0.5f) / float(n)));
  return {c.face, std::clamp(int(c.s * float(n)), 0, n - 1), std::clamp(int(c.t * float(n)), 0, n - 1)};
}

bool is_clipped(const CubeMap& clipped, const std::array<int, 3>& t) {
  return clipped.texel(t[0], t[1], t[2]).maxCoeff() >= 0.5f;
}

// The texels a region may grow through, indexed (f·n + j)·n + i: the clipped ones, each face's
// dilated by a square of half-width ⌈reach/2⌉ (cv::dilate), so that two regions of a face whose
// gap is at most 2⌈reach/2⌉ texels touch. The fill's step crosses face edges.
std::vector<std::uint8_t> passable(const CubeMap& clipped, int reach) {
  const int n = clipped.size();
  std::vector<std::uint8_t> out(std::size_t(6) * n * n);
  for (int f = 0; f < 6; ++f) {
    cv::Mat face(n, n, CV_8U, out.data() + std::size_t(f) * n * n);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) face.at<std::uint8_t>(j, i) = is_clipped(clipped, {f, i, j}) ? 1 : 0;
    const int r = (std::max(0, reach) + 1) / 2;
    if (r > 0) cv::dilate(face, face, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * r + 1, 2 * r + 1)));
  }
  return out;
}

// Flood fill of one region from a seed through passable texels (4-neighbourhood); `label` marks
// visited texels; the region holds the clipped ones.
ClippedSource grow(const CubeMap& clipped, const CubeMap& radiance, const std::vector<std::uint8_t>& pass,
                   std::vector<int>& label, int id, std::array<int, 3> seed) {
  const int n = clipped.size();
  auto index = [n](const std::array<int, 3>& t) { return (std::size_t(t[0]) * n + t[2]) * n + t[1]; };
  std::vector<std::array<int, 3>> texels, stack{seed};
  label[index(seed)] = id;
  while (!stack.empty()) {
    const auto t = stack.back();
    stack.pop_back();
    if (is_clipped(clipped, t)) texels.push_back(t);
    for (const auto& [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const auto u = neighbour(t[0], t[1], t[2], di, dj, n);
      if (label[index(u)] >= 0 || !pass[index(u)]) continue;
      label[index(u)] = id;
      stack.push_back(u);
    }
  }
  return clipped_source(std::move(texels), radiance);
}

}  // namespace

ClippedSource clipped_source(std::vector<std::array<int, 3>> texels, const CubeMap& radiance) {
  const int n = radiance.size();
  ClippedSource s;
  Vec3d dir = Vec3d::Zero();
  for (const auto& t : texels) {
    const double dw = texel_solid_angle(t[1], t[2], n);
    const double y = luminance(radiance.texel(t[0], t[1], t[2])) * dw;
    s.solid_angle_sr += dw;
    s.power += y;
    dir += (y + 1e-30) * texel_direction(t[0], t[1], t[2], n).cast<double>();
  }
  s.dir_world = dir.normalized().cast<float>();
  s.texels = std::move(texels);
  return s;
}

std::vector<ClippedSource> find_clipped_sources(const CubeMap& clipped, const CubeMap& radiance, int max_sources,
                                                int reach_texels) {
  const int n = clipped.size();
  const std::vector<std::uint8_t> pass = passable(clipped, reach_texels);
  std::vector<int> label(std::size_t(6) * n * n, -1);
  std::vector<ClippedSource> all;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (label[(std::size_t(f) * n + j) * n + i] < 0 && is_clipped(clipped, {f, i, j}))
          all.push_back(grow(clipped, radiance, pass, label, int(all.size()), {f, i, j}));
  std::sort(all.begin(), all.end(), [](const ClippedSource& a, const ClippedSource& b) { return a.power > b.power; });
  // The remainder joins the last source kept.
  while (int(all.size()) > std::max(1, max_sources)) {
    ClippedSource& last = all[all.size() - 2];
    const ClippedSource& extra = all.back();
    last.texels.insert(last.texels.end(), extra.texels.begin(), extra.texels.end());
    const Vec3f d = float(last.power) * last.dir_world + float(extra.power) * extra.dir_world;
    if (d.norm() > 0) last.dir_world = d.normalized();
    last.solid_angle_sr += extra.solid_angle_sr;
    last.power += extra.power;
    all.pop_back();
  }
  return all;
}

std::vector<ClippedSource> split_into_parts(const ClippedSource& source, const CubeMap& radiance, int block) {
  std::map<std::array<int, 3>, std::vector<std::array<int, 3>>> groups;
  block = std::max(1, block);
  for (const auto& t : source.texels) groups[{t[0], t[1] / block, t[2] / block}].push_back(t);
  std::vector<ClippedSource> parts;
  for (auto& [key, texels] : groups) parts.push_back(clipped_source(std::move(texels), radiance));
  return parts;
}

CubeMap source_only(const CubeMap& radiance, const ClippedSource& source) {
  CubeMap out(radiance.size());
  for (const auto& t : source.texels) out.set_texel(t[0], t[1], t[2], radiance.texel(t[0], t[1], t[2]));
  out.update_borders();
  return out;
}

CubeMap with_scaled_sources_rgb(const CubeMap& radiance, const std::vector<ClippedSource>& sources,
                                const std::vector<Rgb>& scales) {
  CubeMap out = radiance;
  for (std::size_t k = 0; k < sources.size() && k < scales.size(); ++k)
    for (const auto& t : sources[k].texels)
      out.set_texel(t[0], t[1], t[2], scales[k] * radiance.texel(t[0], t[1], t[2]));
  out.update_borders();
  return out;
}

CubeMap with_scaled_sources(const CubeMap& radiance, const std::vector<ClippedSource>& sources,
                            const std::vector<double>& scales) {
  std::vector<Rgb> rgb;
  for (double s : scales) rgb.push_back(Rgb::Constant(float(s)));
  return with_scaled_sources_rgb(radiance, sources, rgb);
}

double cube_power(const CubeMap& radiance) {
  const int n = radiance.size();
  const std::vector<double> omega = face_solid_angles(n);
  double sum = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        sum += luminance(radiance.texel(f, i, j)) * omega[std::size_t(j) * std::size_t(n) + std::size_t(i)];
  return sum;
}

}  // namespace insitu
