#include "studio/corner_snap.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace insitu {

namespace {

// The structure tensor's eigenvalue ratio λmin / λmax over the window around (x, y): near 0 along
// an edge or in a flat region, of order 1 at a corner.
double corner_ratio(const cv::Mat& gray, int x, int y, int half) {
  const cv::Rect window =
      cv::Rect(x - half, y - half, 2 * half + 1, 2 * half + 1) & cv::Rect(0, 0, gray.cols, gray.rows);
  cv::Mat gx, gy;
  cv::Sobel(gray(window), gx, CV_64F, 1, 0);
  cv::Sobel(gray(window), gy, CV_64F, 0, 1);
  const double a = gx.dot(gx), b = gx.dot(gy), c = gy.dot(gy);
  // Eigenvalues of [[a, b], [b, c]]: (a + c)/2 ± sqrt(((a − c)/2)² + b²).
  const double mean = 0.5 * (a + c), radius = std::hypot(0.5 * (a - c), b);
  return mean + radius > 0 ? (mean - radius) / (mean + radius) : 0.0;
}

}  // namespace

CornerSnap snap_to_corner(const cv::Mat& gray, const Vec2d& click_px, int half_window_px) {
  CornerSnap out;
  out.uv_px = click_px;
  if (gray.empty() || !std::isfinite(click_px.x()) || !std::isfinite(click_px.y())) return out;
  // OpenCV's pixel (i, j) has its centre at (i, j): half a pixel off ours.
  const int x = int(std::floor(click_px.x())), y = int(std::floor(click_px.y()));
  const int h = half_window_px;
  if (x < h + 1 || y < h + 1 || x >= gray.cols - h - 1 || y >= gray.rows - h - 1) return out;
  if (corner_ratio(gray, x, y, h) < 0.1) return out;
  std::vector<cv::Point2f> p = {cv::Point2f(float(click_px.x() - 0.5), float(click_px.y() - 0.5))};
  cv::cornerSubPix(gray, p, cv::Size(h, h), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 40, 0.001));
  const Vec2d snapped(p[0].x + 0.5, p[0].y + 0.5);
  if (!snapped.allFinite() || (snapped - click_px).lpNorm<Eigen::Infinity>() > h) return out;
  return {true, snapped, snapped - click_px};
}

}  // namespace insitu
