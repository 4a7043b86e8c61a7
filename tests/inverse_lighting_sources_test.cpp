// How inverse lighting fits each clipped source (relight/inverse_lighting_sources.h), on synthetic
// pixels whose irradiance is given: a floor of unknown albedo lit by the rest of the room and by
// one clipped window, P = ρ/π (E0 + Σ_j a_j E_j) with ±3 % noise in log P.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/colour.h"
#include "relight/concentrated_light.h"
#include "relight/inverse_lighting_sources.h"

namespace insitu {
namespace {

using inverse_lighting_detail::Albedos;
using inverse_lighting_detail::FitPixel;

constexpr int kPixels = 600;
constexpr double kFloorRho = 0.4;
constexpr double kSunPower = 0.0005, kSkyPower = 0.01;
constexpr double kSunA = 299, kSkyA = 1;  // scales 300 and 2
constexpr int kSeen = 10, kAside = 10;    // sky parts: lighting the floor in view, or mostly aside

// Part 0 is the sun's: E 0.002 per unit of a on a patch (the pixels [100, 200)), nothing
// elsewhere. Parts 1…10 are sky that lights the floor in view: E 0.02 per unit of a, falling off
// from the window, each part's by its own ±3 %. Parts 11…20 are sky whose light falls mostly
// outside the photo: a tenth of that. The rest of the room gives E = 1 everywhere.
double part_irradiance(int j, int i) {
  const double x = double(i) / kPixels;
  if (j == 0) return i >= 100 && i < 200 ? 0.002 : 0.0;
  const double profile = 0.02 * (1.5 - x) * (1 + 0.03 * std::cos(1.7 * j + 9.1 * x * j));
  return j <= kSeen ? profile : 0.1 * profile;
}

std::vector<FitPixel> window_pixels() {
  std::vector<FitPixel> px;
  for (int i = 0; i < kPixels; ++i) {
    FitPixel p;
    p.surface = 0;
    p.e0 = 1.0;
    double e = 1.0;
    for (int j = 0; j <= kSeen + kAside; ++j) {
      const double ej = part_irradiance(j, i);
      p.ek.push_back(ej);
      p.e0 += ej;  // E0: the parts at their lower bound too
      e += (1 + (j == 0 ? kSunA : kSkyA)) * ej;
    }
    const double noise = 0.03 * std::sin(7.3 * double(i) + 1.1);  // ±3 %, deterministic
    p.log_p = std::log(kFloorRho / kPi * e) + noise;
    px.push_back(p);
  }
  return px;
}

InverseLightingResult window_source() {
  InverseLightingResult res;
  SourceFit window;
  window.source.power = kSunPower + (kSeen + kAside) * kSkyPower;
  res.sources.push_back(window);
  for (int j = 0; j <= kSeen + kAside; ++j) {
    PartFit part;
    part.texels.power = j == 0 ? kSunPower : kSkyPower;
    res.parts.push_back(part);
  }
  return res;
}

Albedos unknown_floor(const std::vector<FitPixel>& px) {
  Albedos a;
  double sum = 0;
  for (const FitPixel& p : px) sum += p.log_p - std::log(p.e0) + std::log(kPi);
  a.log_rho = {sum / double(px.size())};
  a.known = {false};
  a.mean = {std::nullopt};
  a.reference = {false};
  a.surfaces = 1;
  return a;
}

// The sky's parts are not told apart (they light the floor alike, and half of them light it
// little), the sun's part is, by its patch. The sky is pooled, one scale for all its parts, which
// the floor's gradient sets; the sun keeps its own. The window's added power is the truth's within
// 15 % and the sun's scale within 20 %. Holding the sky's undetermined parts at the lower bound
// instead (as inverse lighting did) left the half aside at scale 1: the added power came out
// 0.74 of the truth here, and the sky's parts at scales from 1 to 2.3.
TEST(InverseLightingSources, PartsThePhotoCannotTellApartArePooled) {
  const std::vector<FitPixel> px = window_pixels();
  InverseLightingResult res = window_source();
  inverse_lighting_detail::fit_sources(px, unknown_floor(px), res, nullptr);
  ASSERT_TRUE(res.sources[0].determined) << res.sources[0].sigma;
  const double true_added = kSunA * kSunPower + kSkyA * (kSeen + kAside) * kSkyPower;
  std::printf("window added %.4g of a true %.4g; sun's scale %.4g; sky's %.4g … %.4g\n", res.sources[0].added_power,
              true_added, res.parts[0].scale, res.parts[1].scale, res.parts.back().scale);
  EXPECT_NEAR(res.sources[0].added_power, true_added, 0.15 * true_added);
  EXPECT_NEAR(res.parts[0].scale, 1 + kSunA, 0.2 * (1 + kSunA));
  for (std::size_t j = 2; j < res.parts.size(); ++j) EXPECT_EQ(res.parts[j].scale, res.parts[1].scale) << j;
}

// The sun's part cut in two texels, each lighting half its patch with the part's irradiance there:
// the fine parts nest the coarse one, so the fine fit explains the photo as well as the coarse fit
// (the premise of keep_finer_fit) and is kept. A fine fit whose residual is past 1.1 × the coarse
// one's, that leaves a determined source undetermined, or whose residual is not a number, is not.
TEST(InverseLightingSources, AFinerFitIsKeptOnlyWhereItExplainsThePhotoAsWell) {
  const std::vector<FitPixel> coarse_px = window_pixels();
  const Albedos floor = unknown_floor(coarse_px);
  InverseLightingResult coarse = window_source();
  inverse_lighting_detail::fit_sources(coarse_px, floor, coarse, nullptr);
  std::vector<FitPixel> fine_px = coarse_px;
  for (std::size_t i = 0; i < fine_px.size(); ++i) {
    const double e_sun = fine_px[i].ek[0];
    fine_px[i].ek[0] = i < 150 ? e_sun : 0.0;
    fine_px[i].ek.push_back(i < 150 ? 0.0 : e_sun);
  }
  InverseLightingResult fine = coarse;  // warm: from the coarse fit's scales, as the refinement starts
  fine.parts[0].texels.power = 0.5 * kSunPower;
  fine.parts.push_back(fine.parts[0]);
  inverse_lighting_detail::fit_sources(fine_px, floor, fine, nullptr, true);
  std::printf("residual: coarse %.5g, fine %.5g; sun's halves ×%.4g, ×%.4g\n", coarse.residual_rms, fine.residual_rms,
              fine.parts[0].scale, fine.parts.back().scale);
  ASSERT_GT(coarse.residual_rms, 0.0);
  EXPECT_LE(fine.residual_rms, 1.01 * coarse.residual_rms);
  EXPECT_TRUE(inverse_lighting_detail::keep_finer_fit(coarse, fine));

  InverseLightingResult ran_off = fine;
  ran_off.residual_rms = 1.12 * coarse.residual_rms;
  EXPECT_FALSE(inverse_lighting_detail::keep_finer_fit(coarse, ran_off));
  ran_off.residual_rms = 1.08 * coarse.residual_rms;  // within the estimates' noise
  EXPECT_TRUE(inverse_lighting_detail::keep_finer_fit(coarse, ran_off));
  ran_off.residual_rms = std::nan("");
  EXPECT_FALSE(inverse_lighting_detail::keep_finer_fit(coarse, ran_off));
  InverseLightingResult lost = fine;
  lost.sources[0].determined = false;
  EXPECT_FALSE(inverse_lighting_detail::keep_finer_fit(coarse, lost));
}

// A point's cost (concentrated_light.h) is the fit's Cauchy loss with each surface's albedo
// solved: on noise-free pixels of two surfaces of different albedos, P = ρ_s/π (E_base + a E_t),
// it is 0 at the true a whatever the albedos, and grows on either side of it.
TEST(ConcentratedLight, APointsCostIsZeroAtTheTrueScaleWhateverTheAlbedos) {
  constexpr double kTrueA = 299;
  std::vector<FitPixel> px;
  std::vector<double> base, column;
  for (int i = 0; i < 200; ++i) {
    FitPixel p;
    p.surface = i % 2;
    const double rho = p.surface == 0 ? 0.3 : 0.8;
    base.push_back(1.0 + 0.01 * i);
    column.push_back(i >= 50 && i < 120 ? 0.002 : 0.0);  // the sun's patch
    p.log_p = std::log(rho / kPi * (base.back() + kTrueA * column.back()));
    px.push_back(p);
  }
  using inverse_lighting_detail::point_cost;
  EXPECT_NEAR(point_cost(px, base, column, kTrueA, 2), 0.0, 1e-9);
  double previous = 0;
  for (const double f : {1.1, 1.5, 3.0, 10.0}) {
    const double above = point_cost(px, base, column, f * kTrueA, 2);
    const double below = point_cost(px, base, column, kTrueA / f, 2);
    EXPECT_GT(above, previous) << f;
    EXPECT_GT(below, previous) << f;
    previous = std::min(above, below);
  }
  // A pixel the model gives no light is off by far more than any scale: its log residual is 10.
  std::vector<double> dark = base;
  dark[0] = 0;
  EXPECT_GT(point_cost(px, dark, column, kTrueA, 2), std::log1p(90.0 * 90.0));
}

// best_point on three cut texels of one source, each lighting its own patch of a floor (and one
// none of the photo), coarse-fitted at ×51 together: the photo, P = ρ/π (E_base + 1000 E_1),
// shows the light of the second alone. It is the point, at its own scale (1000, not the 50 × 3
// the coarse fit spread). Where the photo shows no added light, no point adds any, not even the
// texel whose light reaches no pixel, whose cost is flat in a.
TEST(ConcentratedLight, ThePointIsTheTexelThePhotoShowsAtItsOwnScale) {
  InverseLightingResult res;
  for (int t = 0; t < 3; ++t) {
    PartFit part;
    part.texels.power = 1e-4;
    part.scale = 51;
    res.parts.push_back(part);
  }
  const auto column = [](int t, int i) { return t < 2 && i / 100 == t ? 0.002 : 0.0; };  // texel 2: none
  for (const double truth : {1000.0, 0.0}) {
    std::vector<FitPixel> px;
    for (int i = 0; i < 200; ++i) {
      FitPixel p;
      p.e0 = 1.0 + 0.002 * i;
      for (int t = 0; t < 3; ++t) p.ek.push_back(column(t, i)), p.e0 += column(t, i);
      p.log_p = std::log(0.5 / kPi * (p.e0 + truth * column(1, i)));
      px.push_back(p);
    }
    const auto [point, a] = inverse_lighting_detail::best_point(px, res, {0, 1, 2}, 1);
    if (truth > 0) {
      EXPECT_EQ(point, 1u);
      EXPECT_NEAR(a, truth, 1e-3 * truth);
    } else {
      EXPECT_EQ(a, 0.0) << "texel " << point;
    }
  }
}

}  // namespace
}  // namespace insitu
