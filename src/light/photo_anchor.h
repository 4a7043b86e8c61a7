// The shots' common rotation anchored to the photo. Registration (shot_registration.h) fixes the
// aims of overlapping shots relative to each other, and takes their common rotation as nominal:
// a set of handheld shots whose misaims do not average out turns the whole light by their mean.
// A room box's straight lines anchor it indoors (room_lines.h). Without a box the light is
// distant, and the photo, whose camera is calibrated, sees the same distant world: its rays are
// the reference.
//
// The photo is resampled into a centred pinhole view (its principal point and focal length as
// calibrated), and matched with each shot as two shots are (shot_features.h: SIFT in a shared
// virtual view, guided, verified by a rotation RANSAC). A match gives the shot's ray u_s (as
// registered) and the photo's world ray u_p. For each group of shots registered together, the
// rotation G with G u_s ≈ u_p over its matches (Kabsch, then RANSAC inliers within 0.25°) turns
// the group. The photo is taken from elsewhere than the shots, so only what is far away satisfies
// one rotation: the near ground's matches are the RANSAC's outliers. A group needs
// kPhotoAnchorMinMatches inliers, and a turn beyond max_turn_deg is not a misaim and is refused.
#pragma once
#include <array>
#include <string>

#include "core/camera.h"
#include "core/image.h"
#include "light/sixshot.h"

namespace insitu {

constexpr int kPhotoAnchorMinMatches = 12;

struct PhotoAnchor {
  std::array<Mat3d, 6> correction = {Mat3d::Identity(), Mat3d::Identity(), Mat3d::Identity(),
                                     Mat3d::Identity(), Mat3d::Identity(), Mat3d::Identity()};  // G of the group
  std::array<bool, 6> anchored{};
  std::array<int, 6> matches{};          // the shot's verified matches with the photo
  std::array<double, 6> turn_deg{};      // the angle of its group's G
  std::array<double, 6> residual_deg{};  // RMS angle of its group's inliers after G
  std::array<std::string, 6> reason;     // why not anchored
};

// `group[s]`: shots with the same value are turned together; `set.aim` as registered.
PhotoAnchor anchor_to_photo(const ShotSet& set, const std::array<int, 6>& group, const Image& photo_linear,
                            const Camera& camera, double max_turn_deg = 10);

// The photo as a centred pinhole view with square pixels of focal length camera.fx, the same
// size (bilinear; outside the photo black).
Image centred_pinhole_view(const Image& photo_linear, const Camera& camera);

}  // namespace insitu
