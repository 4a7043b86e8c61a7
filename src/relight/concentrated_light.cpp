#include "relight/concentrated_light.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>

#include "core/math.h"
#include "light/texel_geometry.h"
#include "relight/clipped_sources.h"
#include "relight/inverse_lighting_sources.h"

namespace insitu::inverse_lighting_detail {

namespace {

// Why cut at all: spread evenly over its part, a sun's energy lands where the face's grid happened
// to fall. The closed room's error with JPEG shots was 8.4, 10.8, 15.7 or 21.7 % as the grid was
// shifted by 0, 2, 4 or 6 texels, the sun sharing its part with 2, 15, 21 or 47 texels
// (docs/validation.md, "Where the part grid falls").
// kConcentrated is the coarse fit's reading of "far brighter than its source": the closed room's
// sky parts lie within ×1.1 of the window's scale and its sun's part at ×4.6 to ×180 as the grid
// moves; 2 also cut the noise of the lamp's and sky's parts (11.3 % at one offset) and 6 missed the
// sun at another (17.9 %).
// kMaxFineParts: two coarse parts of 8 × 8 texels at the fit's 128 face (the sun's and one more).
// With each texel free, 128 made the large dark room's JPEG error 35.6 % (23.5 % at 64); with the
// points it is 18.0 % at 128 and 23.7 % at 64, the other rooms within 0.4 points (docs/validation.md,
// "A concentrated light as a point").
// Only where no reference of known albedo is in the fit: a ball's shadow zone is estimated for the
// coarse parts only (shade_by_balls), and the referenced fit (its convex start, its pinned parts)
// was not measured with fine parts; under AddressSanitizer the studio's demo with a drawn sheet
// took past its 600 s wait with them.

// The parts to cut (ascending) and their texels as parts, each at its part's scale: the most added
// light first, at most kMaxFineParts texels in all.
std::pair<std::vector<int>, std::vector<PartFit>> concentrated_parts(const InverseLightingResult& res,
                                                                     const CubeMap& radiance) {
  std::vector<std::pair<double, int>> candidates;
  for (std::size_t j = 0; j < res.parts.size(); ++j) {
    const PartFit& p = res.parts[j];
    const SourceFit& s = res.sources[std::size_t(p.source)];
    if (s.determined && p.texels.texels.size() >= 2 && p.scale >= kConcentrated * s.scale)
      candidates.push_back({(p.scale - 1) * p.texels.power, int(j)});
  }
  std::sort(candidates.begin(), candidates.end(), std::greater<>());
  std::vector<int> replaced;
  std::vector<PartFit> finer;
  for (const auto& [added, j] : candidates) {
    const PartFit& p = res.parts[std::size_t(j)];
    if (finer.size() + p.texels.texels.size() > kMaxFineParts) continue;
    replaced.push_back(j);
    for (ClippedSource& t : split_into_parts(p.texels, radiance, 1)) finer.push_back({std::move(t), p.source, p.scale});
  }
  std::sort(replaced.begin(), replaced.end());
  return {replaced, finer};
}

// E at each pixel with every part outside `group` at its scale and the group's at the lower bound:
// E0 + Σ_{k ∉ group} (s_k − 1) E_k.
std::vector<double> irradiance_without(const std::vector<FitPixel>& pixels, const InverseLightingResult& res,
                                       const std::vector<std::size_t>& group) {
  std::vector<bool> in_group(res.parts.size(), false);
  for (std::size_t k : group) in_group[k] = true;
  std::vector<double> base(pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    double e = pixels[i].e0;
    for (std::size_t k = 0; k < res.parts.size(); ++k)
      if (!in_group[k]) e += (res.parts[k].scale - 1) * pixels[i].ek[k];
    base[i] = e;
  }
  return base;
}

// The point's own added scale on one texel: the minimum of point_cost over log a in
// [a_inherited/100, 10 a_inherited] by golden-section search (40 steps: to a factor 1.0000004),
// a_inherited being what puts the group's whole added power on the texel.
std::pair<double, double> fit_point_scale(const std::vector<FitPixel>& pixels, const std::vector<double>& base,
                                          const std::vector<double>& column, double a_inherited, int surfaces) {
  const auto cost = [&](double log_a) { return point_cost(pixels, base, column, std::exp(log_a), surfaces); };
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double lo = std::log(a_inherited / 100), hi = std::log(10 * a_inherited);
  for (int step = 0; step < 40; ++step) {
    const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    if (cost(m1) < cost(m2))
      hi = m2;
    else
      lo = m1;
  }
  const double log_a = 0.5 * (lo + hi);
  return {std::exp(log_a), cost(log_a)};
}

}  // namespace

std::pair<std::size_t, double> best_point(const std::vector<FitPixel>& pixels, const InverseLightingResult& res,
                                          const std::vector<std::size_t>& group, int surfaces) {
  double added = 0;
  for (std::size_t k : group) added += (res.parts[k].scale - 1) * res.parts[k].texels.power;
  const std::vector<double> base = irradiance_without(pixels, res, group);
  std::vector<std::pair<double, double>> fits(group.size(), {0.0, INFINITY});  // (a, cost)
  tbb::parallel_for(std::size_t(0), group.size(), [&](std::size_t g) {
    const PartFit& t = res.parts[group[g]];
    if (!(t.texels.power > 0) || !(added > 0)) return;
    std::vector<double> column(pixels.size());
    for (std::size_t i = 0; i < pixels.size(); ++i) column[i] = pixels[i].ek[group[g]];
    fits[g] = fit_point_scale(pixels, base, column, added / t.texels.power, surfaces);
  });
  std::size_t best = 0;
  for (std::size_t g = 1; g < group.size(); ++g)
    if (fits[g].second < fits[best].second) best = g;
  // No better than no added light at all (its light reaches no pixel, or the photo has no room
  // for more): the point adds none, and the refit starts it from the lower bound.
  const double cost_without = point_cost(pixels, base, std::vector<double>(pixels.size(), 0.0), 0.0, surfaces);
  if (!(fits[best].second < cost_without)) return {group[best], 0.0};
  return {group[best], fits[best].first};
}

namespace {

// The cut texels of `group` other than the point, split into its ring (within kRingPitches of
// its direction) and the rest. Each cut part is one texel.
std::pair<std::vector<std::size_t>, std::vector<std::size_t>> ring_and_rest(const InverseLightingResult& res,
                                                                            const std::vector<std::size_t>& group,
                                                                            std::size_t point, int n) {
  const auto direction = [&](std::size_t k) {
    const auto& t = res.parts[k].texels.texels.front();
    return texel_direction(t[0], t[1], t[2], n);
  };
  const Vec3f d_point = direction(point);
  const float cos_ring = std::cos(float(kRingPitches) * 0.5f * kPiF / float(n));
  std::vector<std::size_t> ring, rest;
  for (std::size_t k : group)
    if (k != point) (direction(k).dot(d_point) >= cos_ring ? ring : rest).push_back(k);
  return {ring, rest};
}

// Each source's cut texels (res.parts from `first_fine` on) gathered into three parts: the best
// point at 1 + a; its ring, and the rest, each one part at the lower bound. A column of several
// texels is the sum of theirs (E is linear in the light).
//
// Why a ring: a sun smaller than a texel (0.5° against 0.7° at the fit's 128 face) straddles the
// texels around its own, and the shots' optics and the cube's resampling spread it further. In the
// large dark room the HDR shots put the sun's texel at ×77 500 of the clip level and the other 99
// cut texels at ×332 together, most of it next to the sun; with only a point and the rest, the rest
// (one scale for all of them) took ×22, and the window's added power came out 0.76 of the truth.
// With the ring (11 texels, ×2685 fitted against ×2978 in the HDR shots) the room's JPEG error
// went from 18.0 to 14.3 % at 256 spp and its objects from 0.852 to 0.898; a ring of 3 pitches
// (45 texels) was worse (docs/validation.md, "The point's ring").
void gather_into_points(std::vector<FitPixel>& pixels, InverseLightingResult& res, std::size_t first_fine,
                        const CubeMap& radiance, int surfaces) {
  std::map<int, std::vector<std::size_t>> groups;
  for (std::size_t k = first_fine; k < res.parts.size(); ++k) groups[res.parts[k].source].push_back(k);
  std::vector<PartFit> parts(res.parts.begin(), res.parts.begin() + std::ptrdiff_t(first_fine));
  std::vector<std::vector<std::size_t>> sums;  // per new part: the old parts it sums
  for (std::size_t k = 0; k < first_fine; ++k) sums.push_back({k});
  for (const auto& [source, group] : groups) {
    const auto [point, a] = best_point(pixels, res, group, surfaces);
    parts.push_back({res.parts[point].texels, source, 1 + a});
    sums.push_back({point});
    auto [ring, rest] = ring_and_rest(res, group, point, radiance.size());
    for (std::vector<std::size_t>* ks : {&ring, &rest}) {
      if (ks->empty()) continue;
      std::vector<std::array<int, 3>> texels;
      for (std::size_t k : *ks)
        texels.insert(texels.end(), res.parts[k].texels.texels.begin(), res.parts[k].texels.texels.end());
      parts.push_back({clipped_source(std::move(texels), radiance), source, 1.0});
      sums.push_back(std::move(*ks));
    }
  }
  for (FitPixel& p : pixels) {
    std::vector<double> ek(sums.size(), 0.0);
    std::vector<Rgb> ek_rgb(sums.size(), Rgb::Zero());
    for (std::size_t j = 0; j < sums.size(); ++j)
      for (std::size_t k : sums[j]) ek[j] += p.ek[k], ek_rgb[j] += p.ek_rgb[k];
    p.ek = std::move(ek), p.ek_rgb = std::move(ek_rgb);
  }
  res.parts = std::move(parts);
}

}  // namespace

double point_cost(const std::vector<FitPixel>& pixels, const std::vector<double>& base,
                  const std::vector<double>& column, double a, int surfaces) {
  // A pixel whose E is not positive is off by far more than any scale: log-residual 10.
  std::vector<double> r(pixels.size()), sum(std::size_t(surfaces), 0.0), count(std::size_t(surfaces), 0.0);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const double e = base[i] + a * column[i];
    r[i] = e > 0 ? pixels[i].log_p - std::log(e) : 10.0;
    sum[std::size_t(pixels[i].surface)] += r[i], count[std::size_t(pixels[i].surface)] += 1;
  }
  double cost = 0;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const auto s = std::size_t(pixels[i].surface);
    const double d = (r[i] - sum[s] / count[s]) / kCauchyScale;
    cost += std::log1p(d * d);
  }
  return cost;
}

// Why a point, not each texel free: the fit told apart a sun in one texel from its sky with free
// texels in a synthetic room, but on the closed room's single JPEG shots it spread the sun over
// eight texels at ×15–60 (the truth is thousands) and made the lamp a ring of texels at ×300–3000
// around a dim middle; the objects came out 50 % off with the main camera's shots. A point holds a
// source's concentrated light where one texel explains the photo, and the rest of the cut texels
// stay one part, free to take a wide lamp's light: the main camera's JPEG row went from 37.3 to
// 25.8 % and the large dark room's from 23.5 to 18.0 % (docs/validation.md, "A concentrated light
// as a point"). From the point's own fitted scale, not the coarse fit's, the sources are fitted
// again warm: from the lower bound the robust fit of the 75 unknowns of free texels stalled with
// the lamp at ×2.9 of its ×48.
bool refine_concentrated_parts(std::vector<FitPixel>& pixels, const Albedos& albedos, const InverseLightingInput& in,
                               const std::vector<float>& shares, InverseLightingResult& res) {
  if (std::any_of(pixels.begin(), pixels.end(),
                  [&](const FitPixel& p) { return p.shadow_ball >= 0 || albedos.reference[std::size_t(p.surface)]; }))
    return false;
  auto cut = concentrated_parts(res, *in.radiance);  // not a structured binding: the lambda below takes it
  const std::vector<int>& replaced = cut.first;
  std::vector<PartFit>& finer = cut.second;
  if (replaced.empty()) return false;
  const std::vector<FitPixel> coarse_pixels = pixels;
  const InverseLightingResult coarse = res;
  const PartLights lights{finer.size(), [&](std::size_t k) {
                            return std::make_unique<RoomLight>(source_only(*in.radiance, finer[k].texels), in.room,
                                                               &shares);
                          }};
  replace_part_estimates(pixels, replaced, lights, in, res.parts.size());
  for (auto r = replaced.rbegin(); r != replaced.rend(); ++r) res.parts.erase(res.parts.begin() + *r);
  const std::size_t first_fine = res.parts.size();
  for (PartFit& p : finer) res.parts.push_back(std::move(p));
  gather_into_points(pixels, res, first_fine, *in.radiance, int(albedos.log_rho.size()));
  fit_sources(pixels, albedos, res, in.stop, true);
  if (keep_finer_fit(coarse, res)) return true;
  pixels = coarse_pixels;
  res = coarse;
  return false;
}

}  // namespace insitu::inverse_lighting_detail
