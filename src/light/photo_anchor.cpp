#include "light/photo_anchor.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "light/shot_features.h"

namespace insitu {

namespace {

constexpr int kMaxSidePx = 1200;          // as registration's (RegistrationOptions::max_side_px)
constexpr double kInlierDeg = 0.25;       // a group's rays after G, within a few feature pixels
constexpr double kMaxMatchAngleDeg = 12;  // the guided matching's reach, as between shots

Mat3d aimed_basis_matrix(const ShotSet& set, int s) {
  const ShotBasis b = aimed_basis(set, s);
  Mat3d B;
  B.col(0) = b.right, B.col(1) = b.up, B.col(2) = b.forward;
  return B;
}

// The photo's axes as columns (right, up, forward) in the world: the OpenCV camera's x, −y, z.
Mat3d photo_basis(const Camera& camera) {
  const Mat3d R_world_from_cam = camera.R_cam_from_world.transpose();
  Mat3d B;
  B.col(0) = R_world_from_cam.col(0), B.col(1) = -R_world_from_cam.col(1), B.col(2) = R_world_from_cam.col(2);
  return B;
}

double rms_angle_deg(const std::vector<RayPair>& pairs, const Mat3d& G) {
  double sum = 0;
  for (const RayPair& p : pairs) sum += std::pow(std::asin(std::min(1.0, (G * p.u_a).cross(p.u_b).norm())), 2);
  return pairs.empty() ? 0.0 : rad_to_deg(std::sqrt(sum / double(pairs.size())));
}

// Each shot's matches with the photo, as (u_a: the shot's ray as registered, u_b: the photo's).
std::array<std::vector<RayPair>, 6> photo_matches(const ShotSet& set, const MatchImage& photo) {
  std::array<std::vector<RayPair>, 6> out;
  tbb::parallel_for(0, 6, [&](int s) {
    if (set.shots[std::size_t(s)].empty()) return;
    const MatchImage shot =
        match_image(set.shots[std::size_t(s)], set.hfov_deg[std::size_t(s)], aimed_basis_matrix(set, s), kMaxSidePx);
    for (const RayPair& p : verified_matches(photo, shot, kMaxMatchAngleDeg))
      out[std::size_t(s)].push_back({p.u_b, p.u_a});
  });
  return out;
}

// One group's G from its shots' matches, or the reason there is none.
void anchor_group(const std::array<std::vector<RayPair>, 6>& matches, const std::array<int, 6>& group, int g,
                  double max_turn_deg, PhotoAnchor& out) {
  std::vector<RayPair> pairs;
  for (int s = 0; s < 6; ++s)
    if (group[std::size_t(s)] == g)
      pairs.insert(pairs.end(), matches[std::size_t(s)].begin(), matches[std::size_t(s)].end());
  const std::vector<RayPair> inliers = rotation_inliers(pairs, deg_to_rad(kInlierDeg));
  std::string reason;
  Mat3d G = Mat3d::Identity();
  if (int(inliers.size()) < kPhotoAnchorMinMatches) {
    reason = fmt::format("{} matches with the photo that one rotation explains ({} needed)", inliers.size(),
                         kPhotoAnchorMinMatches);
  } else {
    G = kabsch_rotation(inliers);
    const double turn = rad_to_deg(Eigen::AngleAxisd(G).angle());
    if (turn > max_turn_deg)
      reason = fmt::format("the photo turns it {:.0f}°, more than a misaim", turn), G.setIdentity();
  }
  for (int s = 0; s < 6; ++s) {
    if (group[std::size_t(s)] != g) continue;
    out.anchored[std::size_t(s)] = reason.empty();
    out.reason[std::size_t(s)] = reason;
    out.correction[std::size_t(s)] = G;
    out.turn_deg[std::size_t(s)] = rad_to_deg(Eigen::AngleAxisd(G).angle());
    out.residual_deg[std::size_t(s)] = reason.empty() ? rms_angle_deg(inliers, G) : 0.0;
  }
}

}  // namespace

Image centred_pinhole_view(const Image& photo, const Camera& camera) {
  Image out(photo.width, photo.height, 3, 0.0f);
  const double f = camera.fx, cx = 0.5 * photo.width, cy = 0.5 * photo.height;
  tbb::parallel_for(0, photo.height, [&](int j) {
    for (int i = 0; i < photo.width; ++i) {
      // The view's ray (x, y, 1) in the camera's frame, where the photo sees it.
      const double x = (i + 0.5 - cx) / f, y = (j + 0.5 - cy) / f;
      const double u = camera.fx * x + camera.cx - 0.5, v = camera.fy * y + camera.cy - 0.5;
      const int u0 = int(std::floor(u)), v0 = int(std::floor(v));
      if (u0 < 0 || v0 < 0 || u0 + 1 >= photo.width || v0 + 1 >= photo.height) continue;
      out.set_rgb(i, j, bilinear_rgb(photo, u, v));
    }
  });
  return out;
}

PhotoAnchor anchor_to_photo(const ShotSet& set, const std::array<int, 6>& group, const Image& photo_linear,
                            const Camera& camera, double max_turn_deg) {
  const double hfov_deg = rad_to_deg(2 * std::atan(0.5 * photo_linear.width / camera.fx));
  const MatchImage photo =
      match_image(centred_pinhole_view(photo_linear, camera), hfov_deg, photo_basis(camera), kMaxSidePx);
  const std::array<std::vector<RayPair>, 6> matches = photo_matches(set, photo);
  PhotoAnchor out;
  for (int s = 0; s < 6; ++s) out.matches[std::size_t(s)] = int(matches[std::size_t(s)].size());
  std::vector<int> done;
  for (int s = 0; s < 6; ++s) {
    const int g = group[std::size_t(s)];
    if (std::find(done.begin(), done.end(), g) != done.end()) continue;
    done.push_back(g);
    anchor_group(matches, group, g, max_turn_deg, out);
  }
  return out;
}

}  // namespace insitu
