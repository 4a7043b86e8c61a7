// Verified feature matches between two overlapping shots, for registration (shot_registration.h).
//
// Two neighbouring shots see their overlap near their edges, each stretched by its own
// perspective (about 2× across at 45° off axis), differently: SIFT's descriptors, which are not
// affine-invariant, then rarely agree. So both shots are first resampled (cv::remap) into one
// virtual pinhole view looking along the pair's mean direction c, which covers their nominal
// overlap and a margin for the misaim; there the same surface looks the same in both, up to the
// misaim's small rotation. SIFT (Lowe 2004) runs on each view's log luminance; a feature is
// compared only with the other's features within the misaim's reach (guided matching, Lowe's
// ratio test 0.75 among those), and the matches are verified by RANSAC with the true model, a
// rotation (rotation_inliers). A match's pixels map back to nominal world rays.
#pragma once
#include <opencv2/core.hpp>
#include <vector>

#include "core/image.h"
#include "core/math.h"

namespace insitu {

// A shot ready for matching: its log luminance, shrunk to at most max_side_px on its long side,
// with the focal length of that size; B its nominal axes as columns (right, up, forward).
struct MatchImage {
  Image log_y;  // 1 channel
  double f_px = 0;
  Mat3d B = Mat3d::Identity();
};
MatchImage match_image(const Image& shot, double hfov_deg, const Mat3d& B, int max_side_px);

// A verified match: the nominal world rays u = B·r of one point in shots a and b.
struct RayPair {
  Vec3d u_a, u_b;
};
// The rotation R that best maps the pairs' u_a onto their u_b (Kabsch: the SVD of Σ u_b u_aᵀ,
// its determinant made +1).
Mat3d kabsch_rotation(const std::vector<RayPair>& pairs);

// RANSAC with a rotation's minimal sample, two pairs (2000 draws, a fixed seed): the largest set
// of pairs with |R u_a − u_b| < threshold_rad, refitted once on all of them. A rotation has 3
// degrees of freedom where a homography has 8, so noise and repeated texture, which a homography
// lets through in tens, rarely line up with one.
std::vector<RayPair> rotation_inliers(const std::vector<RayPair>& candidates, double threshold_rad);

// A float image (a log luminance) to 8 bits between its 0.5 % and 99.5 % quantiles over `mask`
// (255 where counted; empty: everywhere).
cv::Mat stretched_8bit(const cv::Mat& m, const cv::Mat& mask);

std::vector<RayPair> verified_matches(const MatchImage& a, const MatchImage& b, double max_angle_deg = 12);

}  // namespace insitu
