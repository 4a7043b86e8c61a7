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
//
// Only pairs whose aims are known compare the same rays (aimed_pairs). A shot pasted at its
// nominal direction is off by the hand's misaim, a few degrees, and its overlap compares
// different surfaces: the ratio then follows the room's gradients, not the exposure. In
// closed_room_handheld (six shots exposed alike, four of them kept at their nominal aims) such
// pairs gave gains of 0.963 to 1.009, and the objects came out 0.962 of Cycles's brightness
// against 0.978 without them (docs/photo-cube.md).
#pragma once
#include <array>

#include "light/photo_anchor.h"
#include "light/room_lines.h"
#include "light/shot_registration.h"
#include "light/sixshot.h"

namespace insitu {

struct ShotGains {
  std::array<Rgb, 6> gain = {Rgb::Ones(), Rgb::Ones(), Rgb::Ones(), Rgb::Ones(), Rgb::Ones(), Rgb::Ones()};
  std::array<int, 6> pairs{};  // overlaps that determined each shot's gain
};

// Which pairs of shots may be compared: comparable[a][b] (symmetric).
using ShotPairs = std::array<std::array<bool, 6>, 6>;
ShotPairs every_pair();  // the aims as given: "register": "none", or a tripod's

// The pairs whose aims are known relative to each other: two shots registered together (one
// group of matched features), or two aimed absolutely, by the room box's lines (not where they
// only levelled the shot: off the box, or without one) or by the photo.
ShotPairs aimed_pairs(const Registration& registration, const LineAnchor* lines, const PhotoAnchor* photo);

// `clipped`: each shot's clipped degree (sixshot.h), or null; `comparable`: the pairs whose
// overlaps are used.
ShotGains overlap_gains(const ShotSet& set, const ShotSet* clipped = nullptr,
                        const ShotPairs& comparable = every_pair());

// Each shot's pixels multiplied by its gain.
void apply_gains(ShotSet& set, const ShotGains& gains);

}  // namespace insitu
