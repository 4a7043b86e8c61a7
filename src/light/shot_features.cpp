#include "light/shot_features.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

namespace insitu {
namespace {

// The virtual view of a pair: a pinhole looking along c (tangent axes e1 right, e2 up), with
// focal length f_px and its principal point at (cx, cy) of a w × h image.
struct PairView {
  Vec3d c, e1, e2;
  double f_px = 0, cx = 0, cy = 0;
  int w = 0, h = 0;
  Vec3d ray(double x, double y) const { return (c + (x - cx) / f_px * e1 - (y - cy) / f_px * e2).normalized(); }
};

// The shot's pixel (corner origin) that sees world direction d, if it does.
bool project(const MatchImage& m, const Vec3d& d, double& px, double& py) {
  const Vec3d r = m.B.transpose() * d;
  if (r[2] <= 1e-6) return false;
  px = 0.5 * m.log_y.width + m.f_px * r[0] / r[2];
  py = 0.5 * m.log_y.height - m.f_px * r[1] / r[2];
  return px >= 0 && px <= m.log_y.width && py >= 0 && py <= m.log_y.height;
}

// The view over the nominal overlap of a and b (a 48 × 48 grid of a's rays tested against b),
// widened by the misaim's reach; empty (w = 0) when they do not overlap.
PairView pair_view(const MatchImage& a, const MatchImage& b, double margin_deg) {
  PairView v;
  v.c = (a.B.col(2) + b.B.col(2)).normalized();
  const Vec3d up = a.B.col(1) + b.B.col(1), up_c = up - up.dot(v.c) * v.c;
  v.e2 = up_c.norm() > 1e-6 ? Vec3d(up_c.normalized()) : v.c.unitOrthogonal();
  v.e1 = v.c.cross(v.e2);  // right = forward × up, as a shot's
  double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
  const int n = 48;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = (i + 0.5) / n * a.log_y.width, y = (j + 0.5) / n * a.log_y.height;
      const Vec3d d = a.B * Vec3d((x - 0.5 * a.log_y.width) / a.f_px, -(y - 0.5 * a.log_y.height) / a.f_px, 1);
      double px, py;
      if (!project(b, d.normalized(), px, py) || d.dot(v.c) <= 0.2 * d.norm()) continue;
      const double t[2] = {d.dot(v.e1) / d.dot(v.c), d.dot(v.e2) / d.dot(v.c)};
      for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], t[k]), hi[k] = std::max(hi[k], t[k]);
    }
  if (lo[0] > hi[0]) return v;
  const double m = std::tan(deg_to_rad(margin_deg));
  v.f_px = std::min(a.f_px, b.f_px);
  const double scale = std::min(1.0, 1600.0 / (v.f_px * std::max(hi[0] - lo[0], hi[1] - lo[1]) + 1));
  v.f_px *= scale;  // at most 1600 pixels on a side
  v.w = int(std::ceil((hi[0] - lo[0] + 2 * m) * v.f_px)), v.h = int(std::ceil((hi[1] - lo[1] + 2 * m) * v.f_px));
  v.cx = (m - lo[0]) * v.f_px, v.cy = (hi[1] + m) * v.f_px;
  return v;
}

// The shot resampled into the view (bilinear), stretched to 8 bits over what it sees; `mask` is
// 255 where the shot sees the view's pixel.
cv::Mat view_of(const MatchImage& m, const PairView& v, cv::Mat& mask) {
  cv::Mat map_x(v.h, v.w, CV_32F), map_y(v.h, v.w, CV_32F);
  mask = cv::Mat::zeros(v.h, v.w, CV_8U);
  for (int y = 0; y < v.h; ++y)
    for (int x = 0; x < v.w; ++x) {
      double px = -10, py = -10;
      if (project(m, v.ray(x + 0.5, y + 0.5), px, py)) mask.at<unsigned char>(y, x) = 255;
      map_x.at<float>(y, x) = float(px - 0.5), map_y.at<float>(y, x) = float(py - 0.5);
    }
  const cv::Mat src(m.log_y.height, m.log_y.width, CV_32F, const_cast<float*>(m.log_y.data.data()));
  cv::Mat warped;
  cv::remap(src, warped, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  const cv::Mat out = stretched_8bit(warped, mask);
  cv::erode(mask, mask, cv::Mat(), cv::Point(-1, -1), 4);  // no features on the seen area's edge
  return out;
}

}  // namespace

cv::Mat stretched_8bit(const cv::Mat& m, const cv::Mat& mask) {
  std::vector<float> seen;
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x)
      if (mask.empty() || mask.at<unsigned char>(y, x)) seen.push_back(m.at<float>(y, x));
  if (seen.size() < 16) return cv::Mat::zeros(m.rows, m.cols, CV_8U);
  const auto q = [&](double p) {
    auto it = seen.begin() + std::ptrdiff_t(p * double(seen.size() - 1));
    std::nth_element(seen.begin(), it, seen.end());
    return *it;
  };
  const float lo = q(0.005), range = std::max(1e-6f, q(0.995) - lo);
  cv::Mat out;
  m.convertTo(out, CV_8U, 255.0 / range, -255.0 * lo / range);
  return out;
}

MatchImage match_image(const Image& shot, double hfov_deg, const Mat3d& B, int max_side_px) {
  // log(Y + ε), ε a thousandth of the median, so that black stays finite.
  cv::Mat y(shot.height, shot.width, CV_32F);
  for (int r = 0; r < shot.height; ++r)
    for (int c = 0; c < shot.width; ++c) {
      const float v = luminance(shot.rgb(c, r));
      y.at<float>(r, c) = std::isfinite(v) ? std::max(0.0f, v) : 0.0f;
    }
  const double scale = std::min(1.0, double(max_side_px) / std::max(shot.width, shot.height));
  if (scale < 1.0)
    cv::resize(
        cv::Mat(y), y,
        cv::Size(std::max(1, int(std::lround(shot.width * scale))), std::max(1, int(std::lround(shot.height * scale)))),
        0, 0, cv::INTER_AREA);
  std::vector<float> v(y.begin<float>(), y.end<float>());
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  cv::log(y + std::max(1e-12f, 1e-3f * v[v.size() / 2]), y);
  MatchImage m;
  m.log_y = Image(y.cols, y.rows, 1);
  std::copy(y.begin<float>(), y.end<float>(), m.log_y.data.begin());
  m.f_px = 0.5 * y.cols / std::tan(0.5 * deg_to_rad(hfov_deg));
  m.B = B;
  return m;
}

std::vector<RayPair> verified_matches(const MatchImage& a, const MatchImage& b, double max_angle_deg) {
  std::vector<RayPair> out;
  const PairView v = pair_view(a, b, max_angle_deg);
  if (v.w < 16 || v.h < 16) return out;
  cv::Mat mask_a, mask_b;
  const cv::Mat img_a = view_of(a, v, mask_a), img_b = view_of(b, v, mask_b);
  const auto sift = cv::SIFT::create(4000, 3, 0.02);
  std::vector<cv::KeyPoint> ka, kb;
  cv::Mat da, db;
  sift->detectAndCompute(img_a, mask_a, ka, da);
  sift->detectAndCompute(img_b, mask_b, kb, db);
  if (ka.size() < 8 || kb.size() < 8) return out;
  // Guided matching: only features within the misaim's reach of each other are compared.
  const double reach_px = std::tan(deg_to_rad(max_angle_deg)) * v.f_px;
  cv::Mat allowed(int(ka.size()), int(kb.size()), CV_8U);
  for (std::size_t i = 0; i < ka.size(); ++i)
    for (std::size_t j = 0; j < kb.size(); ++j)
      allowed.at<unsigned char>(int(i), int(j)) = cv::norm(ka[i].pt - kb[j].pt) <= reach_px ? 1 : 0;
  std::vector<std::vector<cv::DMatch>> knn;
  cv::BFMatcher(cv::NORM_L2).knnMatch(da, db, knn, 2, allowed);
  std::vector<RayPair> candidates;
  for (const auto& m : knn) {
    if (m.empty() || (m.size() == 2 && m[0].distance > 0.75f * m[1].distance)) continue;
    const cv::Point2f pa = ka[std::size_t(m[0].queryIdx)].pt, pb = kb[std::size_t(m[0].trainIdx)].pt;
    candidates.push_back({v.ray(pa.x + 0.5, pa.y + 0.5), v.ray(pb.x + 0.5, pb.y + 0.5)});
  }
  return rotation_inliers(candidates, 1.5 / v.f_px);
}

Mat3d kabsch_rotation(const std::vector<RayPair>& pairs) {
  Mat3d H = Mat3d::Zero();
  for (const RayPair& p : pairs) H += p.u_b * p.u_a.transpose();
  const Eigen::JacobiSVD<Mat3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3d D = Mat3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1 : 1;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

std::vector<RayPair> rotation_inliers(const std::vector<RayPair>& candidates, double threshold_rad) {
  std::vector<RayPair> best;
  if (candidates.size() < 2) return best;
  const auto inliers_of = [&](const Mat3d& R) {
    std::vector<RayPair> in;
    for (const RayPair& p : candidates)
      if ((R * p.u_a - p.u_b).norm() < threshold_rad) in.push_back(p);
    return in;
  };
  std::mt19937 rng(1);  // the same shots register the same way every time
  std::uniform_int_distribution<std::size_t> pick(0, candidates.size() - 1);
  for (int it = 0; it < 2000; ++it) {
    const std::size_t i = pick(rng), j = pick(rng);
    if (i == j || candidates[i].u_a.cross(candidates[j].u_a).norm() < 1e-3) continue;
    std::vector<RayPair> in = inliers_of(kabsch_rotation({candidates[i], candidates[j]}));
    if (in.size() > best.size()) best = std::move(in);
  }
  if (best.size() >= 3) best = inliers_of(kabsch_rotation(best));  // refit on all, once
  return best;
}

}  // namespace insitu
