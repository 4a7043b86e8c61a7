// The room's straight lines as the anchor of the shots' aims. Registration (shot_registration.h)
// fixes the aims of overlapping shots relative to each other; their common rotation, and the aim
// of a shot that overlaps nothing (a main-camera set), it can only take as nominal. A room is a
// Manhattan world: its wall edges, window and door frames and skirting run along three orthogonal
// axes, which a room box declares to be the world's (light/environment_spec.h).
//
// Each shot's line segments (LSD, von Gioi et al. 2012: OpenCV's createLineSegmentDetector, on its
// log luminance shrunk to 1200 pixels) longer than 3 % of its diagonal give, through the shot's
// aim, the normal n of the plane through the eye and the line. A line along world axis e_k has
// n · e_k = 0, so a rotation G of a group of shots (those registered together, or one alone) is
// found by Ceres from
//   Σ_segments w ρ((G n)_k(n)² / σ²) + |log G|² / σ_p²
// with k(n) the axis the segment is nearest to being along, w its length, σ = 0.5°, ρ Cauchy's
// loss and σ_p = 10°; the assignment is redone after each fit (three rounds, gates of 6°, 3°, 2°).
// A segment whose plane holds two axes (a horizontal line seen at eye level) says nothing of the
// rotation about the third and is not counted. A group needs 10 segments along each of two axes
// to be anchored. The turn's precision σ is Ceres's covariance scaled by the residuals' own
// spread; a turn within 3σ is not told from the lines' noise and is not applied (shots aimed
// exactly stay exactly as they are).
//
// Without a room box nothing says where the walls run, but world +y is still up (conventions.md),
// and a room's, a street's or a hall's vertical edges are plumb: the vertical lines alone level each
// group. Only the segments along y enter the fit, G turns about horizontal axes only (ω_y = 0), the
// yaw stays as registered, and a group needs 10 vertical segments.
#pragma once
#include <array>
#include <string>

#include "light/sixshot.h"

namespace insitu {

// Which of the world's axes the lines are taken to run along.
enum class LineAxes {
  room,      // x, y and z: a room box's walls (the full turn)
  vertical,  // y only: plumb edges level the shots (the tilt), the yaw stays as registered
};

struct LineAnchor {
  LineAxes axes = LineAxes::room;
  std::array<Mat3d, 6> correction = {Mat3d::Identity(), Mat3d::Identity(), Mat3d::Identity(), Mat3d::Identity(),
                                     Mat3d::Identity(), Mat3d::Identity()};  // G of each shot's group
  std::array<bool, 6> anchored{};
  std::array<double, 6> turn_deg{};           // the angle of G (0 where not applied)
  std::array<double, 6> sigma_deg{};          // its precision from the lines' scatter
  std::array<std::array<int, 3>, 6> lines{};  // the shot's segments along x, y, z
  std::array<std::string, 6> reason;          // why not anchored
  // LineAxes::room: the group's lines turn it by more than kMaxHandTurnDeg, which is the box drawn
  // off the real walls, not a misaim; the turn it would have made. The group is then levelled by
  // its plumb lines as with LineAxes::vertical (anchored, correction and lines are those), and
  // `reason` says why.
  std::array<bool, 6> off_box{};
  std::array<double, 6> off_box_turn_deg{};
};

// A hand aims a phone a few degrees off (the handheld validation's σ is 2° about each axis: a turn
// past 15° is 4σ of its norm, p < 10⁻³); the lines' first gate is 6° and their prior's σ 10°. A room
// box's axes that turn a group by more than this are not the room's walls (a box drawn askew, or a
// calibration whose frame is turned from the walls), and the lines are not used to turn it.
inline constexpr double kMaxHandTurnDeg = 15.0;

// `group[s]`: shots with the same value are turned together (registration's groups).
LineAnchor anchor_to_room_axes(const ShotSet& set, const std::array<int, 6>& group, LineAxes axes = LineAxes::room);

}  // namespace insitu
