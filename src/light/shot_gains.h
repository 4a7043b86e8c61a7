// Exposure and white balance matched between overlapping shots. A phone left on auto changes its
// exposure and white balance from shot to shot; where two shots see the same surface, their
// linear radiance should agree, and the ratio says by how much each shot is off.
//
// For every pair of shots that overlap (as aimed: ShotSet::aim), a grid of 64 × 48 of shot a's
// rays is looked up in both; where both see the ray unclipped and above black, each channel's
// log ratio log(I_b / I_a) is taken, and the pair's robust offset m_ab is its median (g_a I_a =
// g_b I_b wants log g_a − log g_b = m_ab). The log gains then solve, per channel, the least
// squares of OpenCV's GainCompensator (Brown and Lowe 2007) in the log domain:
//   Σ_pairs (log g_a − log g_b − m_ab)² / σ_m² + Σ_shots (log g_s)² / σ_g²
// with σ_m = 0.01 (a pair agrees to 1 %) and σ_g = 1: the pairs fix the gains relative to each
// other (the weak prior only makes the system regular). Their common factor is then set so that
// the median shot keeps its exposure (the median of the log gains is 0): one shot that the
// camera exposed or balanced differently is brought to the others, not the others halfway to it,
// and the set's exposure (EXIF or the estimate, environment.h) is kept. A shot without a usable
// overlap keeps gain 1.
#pragma once
#include <array>

#include "light/sixshot.h"

namespace insitu {

struct ShotGains {
  std::array<Rgb, 6> gain = {Rgb::Ones(), Rgb::Ones(), Rgb::Ones(), Rgb::Ones(), Rgb::Ones(), Rgb::Ones()};
  std::array<int, 6> pairs{};  // overlaps that determined each shot's gain
};

// `clipped`: each shot's clipped degree (sixshot.h), or null.
ShotGains overlap_gains(const ShotSet& set, const ShotSet* clipped = nullptr);

// Each shot's pixels multiplied by its gain.
void apply_gains(ShotSet& set, const ShotGains& gains);

}  // namespace insitu
