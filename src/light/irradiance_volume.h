// The irradiance volume (Greger et al. 1998, "The Irradiance Volume"): the fast
// path's answer to parallax, which the 2011 thesis named its main open problem (look the light up
// by the vertex's world position, not only its normal). The room's light (room_light.h: the
// emitting box and its openings) is projected on the 9 spherical harmonics at probes on a regular
// grid inside the room box; a lookup interpolates the coefficients trilinearly and evaluates
//   E(x, n) = Σ_lm Â_l L_lm(x) Y_lm(n)        (Ramamoorthi & Hanrahan 2001; sh9_irradiance)
// clamped at 0 (SH9 of a sun rings negative on its far side).
//
// A probe's coefficients L_lm(p) = ∫ L_room(p, ω) Y_lm(ω) dω are estimated by Monte Carlo with two
// strategies, a sample of the room's light (which finds the sun through a window) and a uniform
// direction on the sphere (which finds everything else), combined by the balance heuristic:
//   L̂_lm = 1/N Σ_{both samples of each pair} L(ω) Y_lm(ω) / (p_room(ω) + 1/4π),
// their random numbers stratified (Latin hypercube).
// Probes lie about 1/8 of the box's larger extent apart (at least 2 per axis), pulled 10⁻³ of the
// box inside its faces; N = 2048 pairs. No visibility: like the other irradiance modes it shades
// without shadows, so a real-time engine could read the same grid.
#pragma once
#include <vector>

#include "light/irradiance.h"
#include "light/room_light.h"

namespace insitu {

class IrradianceVolume {
 public:
  // `stop` (core/stop.h) is looked at before each probe.
  IrradianceVolume(const RoomLight& room, const RoomBox& box, int cells = 8, int samples = 2048,
                   const std::atomic<bool>* stop = nullptr);
  Rgb irradiance(const Vec3f& x, const Vec3f& normal_unit) const;
  // The estimator at one point, for the grid and the tests.
  static Sh9 project(const RoomLight& room, const Vec3f& p, int samples, std::uint64_t key);
  Eigen::Vector3i probes() const { return n_; }

 private:
  Vec3f min_, step_;
  Eigen::Vector3i n_;
  std::vector<Sh9> probes_;  // x fastest, then y, then z
};

}  // namespace insitu
