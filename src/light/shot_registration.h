// Registration of the six shots: where each shot really looked. Nobody aims a phone exactly; a
// shot pasted onto its nominal face moves the window, the lamps and the sun patch by its misaim.
//
// Where shots overlap (an ultra-wide lens: about 110° across, so each shot reaches into its
// neighbours), their features are matched (SIFT, Lowe 2004, on the log luminance) and each pair's
// matches are verified by RANSAC (light/shot_features.h). The shots share one centre, so the
// matched rays satisfy R_a·B_a·r_a = R_b·B_b·r_b, with B the nominal axes (sixshot.h shot_basis)
// and R the aim to recover. A rotation-only bundle adjustment (Ceres; the model of OpenCV's
// BundleAdjusterRay, Brown and Lowe 2007, without the focal lengths) minimises over the aims
//   Σ_matches ρ(|R_a u_a − R_b u_b|² / σ_m²) + Σ_shots |log R_s|² / σ_p²
// where u = B·r are the nominal world rays, σ_m one feature pixel in angle, ρ Cauchy's loss, and
// the prior σ_p = 10° anchors each shot to its nominal direction: the matches fix the aims
// relative to each other, the prior fixes their common rotation (the mean misaim is taken as 0).
//
// A shot that overlaps no neighbour, or whose matches do not agree, keeps its nominal direction,
// and says why.
#pragma once
#include <array>
#include <string>

#include "light/sixshot.h"

namespace insitu {

struct ShotAim {
  bool registered = false;
  std::string reason;       // why not, when not registered
  double rotation_deg = 0;  // the angle of R_aim
  // R_aim's rotation vector in the shot's own nominal axes: about its up (yaw), its right
  // (pitch) and its forward (roll), in degrees.
  double yaw_deg = 0, pitch_deg = 0, roll_deg = 0;
  double residual_deg = 0;  // RMS angle between its matched rays and its neighbours' after the fit
  int matches = 0;          // verified matches with its neighbours
};

struct Registration {
  std::array<Mat3d, 6> aim = {Mat3d::Identity(), Mat3d::Identity(), Mat3d::Identity(),
                              Mat3d::Identity(), Mat3d::Identity(), Mat3d::Identity()};
  std::array<ShotAim, 6> shots;
  bool overlap = false;                           // whether any two shots' nominal views overlap
  std::array<int, 6> group = {0, 1, 2, 3, 4, 5};  // shots registered together share their group
};

// R_aim's angle and its rotation vector along the shot's nominal axes (ShotAim's fields).
void describe_aim(const Mat3d& aim, const ShotBasis& nominal, ShotAim& a);

struct RegistrationOptions {
  int max_side_px = 1200;        // features are found on each shot shrunk to this (time, memory)
  double prior_sigma_deg = 10;   // σ_p
  double max_rotation_deg = 25;  // a fit that turns a shot further than this is not a misaim
  double min_overlap = 0.03;     // a pair is tried when its nominal overlap is this fraction of a shot
};

Registration register_shots(const ShotSet& set, const RegistrationOptions& options = {});

// The fraction of shot a's pixels (a 24 × 24 grid) whose ray falls inside shot b, both nominal.
double nominal_overlap(const ShotSet& set, int a, int b);

}  // namespace insitu
