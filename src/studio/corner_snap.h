// Snapping a click to the nearest image corner: OpenCV's cornerSubPix, the
// iteration that moves a point to where every image gradient in a window is orthogonal to the
// vector from the point (Förstner & Gülch 1987). It converges on a corner or a saddle (a
// checkerboard's cross), and drifts along an edge or in flat regions, so a snap is kept only
// where the window has a corner (the structure tensor's smaller eigenvalue, cv::cornerMinEigenVal,
// at least a tenth of the larger) and the point moved no farther than the window's half size.
#pragma once
#include <opencv2/core.hpp>

#include "core/math.h"

namespace insitu {

struct CornerSnap {
  bool snapped = false;         // false: keep the click as it was
  Vec2d uv_px = Vec2d::Zero();  // the snapped position (or the click)
  Vec2d offset_px = Vec2d::Zero();
};

// `gray`: one channel, CV_32F (any scale). `click_px` in pixel coordinates (DESIGN.md: the top-left
// pixel's centre is (0.5, 0.5)). `half_window_px`: the search window's half size.
CornerSnap snap_to_corner(const cv::Mat& gray, const Vec2d& click_px, int half_window_px = 5);

}  // namespace insitu
