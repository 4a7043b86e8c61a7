#include "relight/inverse_lighting.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>

#include "core/colour.h"
#include "core/stop.h"
#include "relight/concentrated_light.h"
#include "relight/fit_resolution.h"
#include "relight/inverse_lighting_pixels.h"
#include "relight/inverse_lighting_solve.h"
#include "relight/inverse_lighting_sources.h"
#include "relight/linear_variance.h"

namespace insitu {

namespace {

using inverse_lighting_detail::Albedos;
using inverse_lighting_detail::Columns;
using inverse_lighting_detail::estimate_irradiance;
using inverse_lighting_detail::Fit;
using inverse_lighting_detail::fit_sources;
using inverse_lighting_detail::FitPixel;
using inverse_lighting_detail::gather_pixels;
using inverse_lighting_detail::initial_albedos;
using inverse_lighting_detail::refine_concentrated_parts;
using inverse_lighting_detail::solve;

// A channel's fit of the determined sources' colour: pixels whose E is E0_c + Σ_k m_k A_k,c, with
// A_k,c the light the luminance fit added from source k in channel c (Σ over its parts of
// (s_j − 1) E_j,c) and m_k ≥ 0 the unknown multiplier; one ρ per surface and channel as before
// (a reference's known albedo taken as grey: a white sheet, a grey card). m_k = 1 is the clipped
// value's own colour.
std::vector<FitPixel> channel_pixels(const std::vector<FitPixel>& pixels, const InverseLightingResult& res,
                                     const std::vector<int>& sources, int c) {
  std::vector<FitPixel> out;
  for (const FitPixel& p : pixels) {
    if (!(p.p_rgb[c] > 0) || !(p.e0_rgb[c] > 0)) continue;  // log P, log E undefined
    FitPixel q;
    q.surface = p.surface;
    q.log_p = std::log(double(p.p_rgb[c]));
    q.e0 = p.e0_rgb[c];
    q.ek.assign(sources.size(), 0.0);
    for (std::size_t j = 0; j < res.parts.size(); ++j)
      for (std::size_t k = 0; k < sources.size(); ++k)
        if (res.parts[j].source == sources[k]) q.ek[k] += (res.parts[j].scale - 1) * p.ek_rgb[j][c];
    out.push_back(std::move(q));
  }
  return out;
}

// The colour of the light each determined source adds, where a clipped texel kept none (white, or
// the colour of whichever channels clipped last): each channel fitted as the luminance was, with
// the sources' parts held at their fitted ratios (one multiplier m_k,c per source and channel). The
// colour is m / Y(m), so the added luminance stays the luminance fit's. It is determined when every
// channel's σ is at most a tenth of Y(m). It is applied only when it departs from the clipped
// colour (1) by more than max(3σ, 0.1) in some channel: a cast smaller than that is within what
// the model's own approximations (grey references, the box's interreflections) can bias, so the
// simpler model — the clipped colour — is kept (docs/validation.md: on the closed room a 2–7 %
// cast fitted to near-white sources made the objects 1.8 % too red, against 0.8 % without).
void fit_colours(const std::vector<FitPixel>& pixels, const InverseLightingInput& in, InverseLightingResult& res) {
  std::vector<int> sources;
  for (std::size_t k = 0; k < res.sources.size(); ++k)
    if (res.sources[k].determined && res.sources[k].scale > 1) sources.push_back(int(k));
  if (sources.empty()) return;
  Columns columns;
  for (std::size_t k = 0; k < sources.size(); ++k) columns.push_back({int(k)});
  std::vector<Rgb> m(sources.size(), Rgb::Ones()), sigma(sources.size(), Rgb::Constant(INFINITY));
  for (int c = 0; c < 3; ++c) {
    const std::vector<FitPixel> px = channel_pixels(pixels, res, sources, c);
    if (px.size() < 16) return;
    const Fit fit = solve(px, columns, initial_albedos(px, in), in.stop);
    for (std::size_t k = 0; k < sources.size(); ++k) {
      Eigen::VectorXd g = Eigen::VectorXd::Zero(fit.jtj.rows());
      g[Eigen::Index(k)] = 1;
      m[k][c] = float(fit.a[k]);
      sigma[k][c] = float(std::sqrt(variance_along(fit.jtj, g, fit.sigma_r)));
    }
  }
  for (std::size_t k = 0; k < sources.size(); ++k) {
    SourceFit& s = res.sources[std::size_t(sources[k])];
    const float y = luminance(m[k]);
    if (!(y > 0)) continue;
    s.colour_sigma = sigma[k] / y;
    if (!(sigma[k].maxCoeff() <= 0.1f * y)) continue;
    s.colour = m[k] / y;
    s.colour_determined = true;
    const Rgb margin = (3.0f * s.colour_sigma).max(Rgb::Constant(0.1f));  // max(3σ, 0.1)
    s.colour_applied = ((s.colour - 1.0f).abs() > margin).any();
  }
}

void describe(InverseLightingResult& res) {
  int determined = 0;
  for (const SourceFit& s : res.sources) determined += s.determined ? 1 : 0;
  const int n = int(res.sources.size());
  res.status = determined == n ? "fitted" : determined > 0 ? "partly" : "undetermined";
  double solid_angle = 0;
  for (const SourceFit& s : res.sources) solid_angle += s.determined ? 0 : s.source.solid_angle_sr;
  if (determined == n) {
    res.message = fmt::format("{} clipped source(s) recovered against {} photo pixels on {} surface(s){}", n,
                              res.pixels, res.surfaces, res.reference_surfaces > 0 ? " with a reference albedo" : "");
    return;
  }
  double share = 0;
  for (const SourceFit& s : res.sources) share += s.determined ? 0 : s.source.power;
  share /= std::max(1e-300, res.cube_power);
  const std::string what = fmt::format(
      "{} of {} clipped source(s) ({:.3g} sr, {:.2g}% of the shots' light at their lower bound) not determined by the "
      "photo "
      "({} pixels on {} surface(s)) stay at the lower bound",
      n - determined, n, solid_angle, 100 * share, res.pixels, res.surfaces);
  const std::string advice =
      "give a local-scene plane's mean_albedo (a white sheet about 0.8, the floor's mean), or brackets short enough "
      "that "
      "nothing clips";
  if (res.missing_irradiance)
    res.message = fmt::format(
        "{}; the photo shows its surfaces get {:.0f}% more light than that, but not from which "
        "direction, so the objects may be too dark (by up to about that much); {}",
        what, 100 * *res.missing_irradiance,
        res.reference_surfaces > 0 ? "brackets short enough that nothing clips" : advice);
  else
    res.message = fmt::format(
        "{}; if one is a key light (the sun, a lamp) the objects and their shadows are too dark; {}", what, advice);
}

// The clipped texels less, under distant light, those that look into a plane of the local scene
// (against its normal as the camera sees it): they show the ground, not light. The render takes
// the ground's light from the photo (the catcher), and from the cube only where the photo does
// not reach; scaled as a source, a texel at the open floor's horizon became the floor's radiance
// beyond the photo's edge, 250× too bright, seen by the objects as fireflies. In a room box the
// cube's floor is the box's own face, lit and lighting as the room light places it: kept.
CubeMap light_texels(const CubeMap& clipped, const InverseLightingInput& in) {
  CubeMap out = clipped;
  if (in.room) return out;
  const Vec3f eye = in.camera ? Vec3f(in.camera->eye_world().cast<float>()) : Vec3f(Vec3f::Zero());
  for (const FitPlane& pl : in.planes) {
    const Vec3f n = (eye - pl.point).dot(pl.normal) >= 0 ? pl.normal : Vec3f(-pl.normal);
    for (int f = 0; f < 6; ++f)
      for (int j = 0; j < out.size(); ++j)
        for (int i = 0; i < out.size(); ++i)
          if (texel_direction(f, i, j, out.size()).dot(n) < 0) out.set_texel(f, i, j, Rgb::Zero());
  }
  out.update_borders();
  return out;
}

// The pixels fitted, and each reference's own and in its shadow.
void count_pixels(const std::vector<FitPixel>& pixels, const InverseLightingInput& in, InverseLightingResult& res) {
  res.pixels = int(pixels.size());
  const int first = int(in.planes.size() + 6), last = first + int(in.references.size());
  for (const FitPixel& p : pixels) {
    if (p.surface >= first && p.surface < last) ++res.references[std::size_t(p.surface - first)].used;
    if (p.shadow_ball >= 0) ++res.references[std::size_t(p.shadow_ball)].shadow;
  }
}

// Each source's parts: blocks of base_block² texels, coarser when the clipped area is large (at
// most ~48 unknowns).
std::vector<PartFit> make_parts(const std::vector<ClippedSource>& sources, const CubeMap& radiance, int base_block) {
  std::size_t clipped_texels = 0;
  for (const ClippedSource& s : sources) clipped_texels += s.texels.size();
  const int block = std::max(base_block, int(std::ceil(std::sqrt(double(clipped_texels) / 48.0))));
  std::vector<PartFit> parts;
  for (std::size_t k = 0; k < sources.size(); ++k)
    for (ClippedSource& part : split_into_parts(sources[k], radiance, block))
      parts.push_back({std::move(part), int(k)});
  return parts;
}

// The fit on the cubes as given (recover_clipped_sources shrinks them first).
InverseLightingResult recover_at_resolution(const InverseLightingInput& in) {
  InverseLightingResult res;
  res.fit_face_size = in.radiance->size();
  std::vector<ClippedSource> sources;
  // Parts of about (n/16)² texels (at least 2²; make_parts). Regions closer than a part's width
  // are one source: the fit resolves nothing finer, and a speck beside a window's edge (JPEG
  // ringing, texture at the clip level) would otherwise be a source of its own, free to take what
  // the fit leaves (raised grey ball: a one-texel speck ×2769, docs/validation.md).
  const int base_block = std::max(2, in.radiance->size() / 16);
  if (in.clipped)
    sources = find_clipped_sources(light_texels(*in.clipped, in), *in.radiance, kMaxClippedSources, base_block);
  const double total = cube_power(*in.radiance);
  for (const ClippedSource& s : sources) {
    res.sources.push_back({s});
    res.clipped_power_share += total > 0 ? s.power / total : 0;
    res.cube_power = total;
  }
  if (sources.empty()) {
    res.status = "none";
    res.message = "no light clipped in the shots";
    return res;
  }
  res.parts = make_parts(sources, *in.radiance, base_block);
  const CubeMap rest = with_scaled_sources(*in.radiance, sources, std::vector<double>(sources.size(), 0.0));
  // Which texels c saw through the openings: the box's alone, the same for every light below.
  const std::vector<float> shares =
      in.room ? RoomLight(CubeMap(1), in.room).opening_shares(in.radiance->size()) : std::vector<float>{};
  RoomLight room0(rest, in.room, &shares);
  // Each part's light: the cube with its texels alone (estimate_irradiance builds a few at a time).
  const inverse_lighting_detail::PartLights lights{
      res.parts.size(), [&](std::size_t k) {
        return std::make_unique<RoomLight>(source_only(*in.radiance, res.parts[k].texels), in.room, &shares);
      }};
  std::vector<FitPixel> pixels = gather_pixels(in, room0, res.references);
  estimate_irradiance(pixels, room0, lights, in);
  inverse_lighting_detail::light_balls_from_the_floor(pixels, rest, in);
  std::vector<const ClippedSource*> part_texels;
  for (const PartFit& p : res.parts) part_texels.push_back(&p.texels);
  inverse_lighting_detail::shade_by_balls(pixels, rest, *in.radiance, part_texels, in);
  count_pixels(pixels, in, res);
  const Albedos albedos = initial_albedos(pixels, in);
  res.surfaces = albedos.surfaces;
  res.reference_surfaces = albedos.references;
  if (pixels.size() >= 16) {
    fit_sources(pixels, albedos, res, in.stop);
    refine_concentrated_parts(pixels, albedos, in, shares, res);
  }
  fit_colours(pixels, in, res);
  return res;
}

}  // namespace

InverseLightingResult recover_clipped_sources(const InverseLightingInput& in) {
  InverseLightingResult res;
  if (!in.clipped || in.radiance->size() <= kFitFaceSize) {
    res = recover_at_resolution(in);
  } else {
    const FitCubes shrunk = shrink_for_fit(*in.radiance, *in.clipped);
    InverseLightingInput coarse = in;
    coarse.radiance = &shrunk.radiance, coarse.clipped = &shrunk.clipped;
    res = recover_at_resolution(coarse);
    map_to_full_resolution(res, *in.radiance, *in.clipped);
  }
  if (res.status != "none") describe(res);
  return res;
}

bool InverseLightingResult::any_determined() const {
  return std::any_of(sources.begin(), sources.end(), [](const SourceFit& s) { return s.determined; });
}

// Each part's texels L0 become L0 ⊙ (1 + (s − 1) colour): the added light in its source's colour.
CubeMap InverseLightingResult::apply(const CubeMap& radiance) const {
  std::vector<ClippedSource> src;
  std::vector<Rgb> scale;
  for (const PartFit& p : parts) {
    src.push_back(p.texels);
    const SourceFit& s = sources[std::size_t(p.source)];
    scale.push_back(1.0f + float(p.scale - 1) * (s.colour_applied ? s.colour : Rgb::Ones()));
  }
  return with_scaled_sources_rgb(radiance, src, scale);
}

}  // namespace insitu
