#include "relight/unseen_outside.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/colour.h"
#include "relight/fit_resolution.h"
#include "relight/inverse_lighting_pixels.h"
#include "relight/inverse_lighting_solve.h"
#include "relight/linear_variance.h"

namespace insitu {

namespace {

using inverse_lighting_detail::FitPixel;

// u: the luminance-median texel of those c saw wholly through an opening (zero when there is none).
Rgb median_seen_outside(const CubeMap& cube, const std::vector<float>& shares) {
  std::vector<std::pair<float, Rgb>> seen;
  for_each_texel_of_share(shares, cube.size(), 1.0f, [&](int f, int i, int j) {
    seen.emplace_back(luminance(cube.texel(f, i, j)), cube.texel(f, i, j));
  });
  if (seen.empty()) return Rgb::Zero();
  const auto mid = seen.begin() + std::ptrdiff_t(seen.size() / 2);
  std::nth_element(seen.begin(), mid, seen.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return mid->second;
}

// The fit's pixels with E_w as E0 and E_u as their one column (estimate_irradiance adds each
// part's estimate to E0; here E0 is the light without the unseen outside, so that a = f ≥ 0).
std::vector<FitPixel> fill_pixels(const InverseLightingInput& in, const CubeMap& cube, const std::vector<float>& shares,
                                  const Rgb& unit) {
  RoomBox without = *in.room, unit_only = *in.room;
  without.unseen_outside = Rgb::Zero();
  unit_only.unseen_outside = unit;
  const RoomLight room_w(cube, without, &shares);
  const CubeMap black(cube.size());
  const inverse_lighting_detail::PartLights fill{
      1, [&](std::size_t) { return std::make_unique<RoomLight>(black, unit_only, &shares); }};
  std::vector<ReferenceUse> uses;
  std::vector<FitPixel> pixels = inverse_lighting_detail::gather_pixels(in, room_w, uses);
  inverse_lighting_detail::estimate_irradiance(pixels, room_w, fill, in);
  for (FitPixel& p : pixels) {
    p.e0_rgb -= p.ek_rgb[0];
    p.e0 = luminance(p.e0_rgb);
  }
  pixels.erase(std::remove_if(pixels.begin(), pixels.end(), [](const FitPixel& p) { return !(p.e0 > 0); }),
               pixels.end());
  return pixels;
}

void judge(const std::vector<FitPixel>& pixels, const inverse_lighting_detail::Fit& fit, UnseenOutsideFit& out) {
  out.scale = fit.a[0];
  Eigen::VectorXd g = Eigen::VectorXd::Zero(fit.jtj.rows());
  g[0] = 1;
  out.sigma = std::sqrt(variance_along(fit.jtj, g, fit.sigma_r));
  if (!(out.sigma <= 0.5 * std::max(out.scale, 1.0))) {
    out.status = "undetermined";
    out.message = fmt::format(
        "the light through the windows from where the shots were not taken is not determined by the photo "
        "(x{:.2f} +- {:.2f} of the sky the shots saw): the walls stand in for it",
        out.scale, out.sigma);
    return;
  }
  double share = 0;
  for (const FitPixel& p : pixels) share += out.scale * p.ek[0] / (p.e0 + out.scale * p.ek[0]);
  out.light_share = pixels.empty() ? 0 : share / double(pixels.size());
  out.status = "fitted";
  out.message = fmt::format(
      "the light through the windows from where the shots were not taken: x{:.2f} +- {:.2f} "
      "of the sky the shots saw, {:.1f} % of the light on the photo's surfaces",
      out.scale, out.sigma, 100 * out.light_share);
}

}  // namespace

std::optional<Rgb> UnseenOutsideFit::radiance() const {
  if (status != "fitted") return std::nullopt;
  return Rgb(float(scale) * unit);
}

UnseenOutsideFit fit_unseen_outside(const InverseLightingInput& given) {
  UnseenOutsideFit out;
  out.status = "none";
  if (!given.room || given.room->openings.empty()) return out;
  InverseLightingInput in = given;
  in.clipped = nullptr;
  in.references.erase(std::remove_if(in.references.begin(), in.references.end(),
                                     [](const FitReference& r) { return r.ball.has_value(); }),
                      in.references.end());
  // Shrunk as the clipped light's fit shrinks it (its clipped cube, unused here, is the radiance).
  const CubeMap cube = shrink_for_fit(*given.radiance, *given.radiance).radiance;
  const std::vector<float> shares = RoomLight(CubeMap(1), in.room).opening_shares(cube.size());
  out.unit = median_seen_outside(cube, shares);
  if (!(luminance(out.unit) > 0)) {
    out.message = "the shots saw nothing bright through the room box's openings";
    return out;
  }
  in.radiance = &cube;
  const std::vector<FitPixel> pixels = fill_pixels(in, cube, shares, out.unit);
  out.pixels = int(pixels.size());
  if (pixels.size() < 16) {
    out.status = "undetermined";
    out.message = "too few photo pixels on the room's surfaces to fit the light through the windows";
    return out;
  }
  const std::vector<double> start{1.0};
  judge(pixels,
        inverse_lighting_detail::solve(pixels, {{0}}, inverse_lighting_detail::initial_albedos(pixels, in), in.stop,
                                       &start),
        out);
  return out;
}

}  // namespace insitu
