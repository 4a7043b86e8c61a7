#include "studio/preview_png.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/colour.h"

namespace insitu {

namespace {

uchar byte_of(float linear) { return cv::saturate_cast<uchar>(255 * linear_to_srgb(std::clamp(linear, 0.0f, 1.0f)) + 0.5f); }

}  // namespace

std::string srgb_png(const Image& linear, const Image* red_where_positive, int max_side_px) {
  cv::Mat bgr(linear.height, linear.width, CV_8UC3);
  for (int y = 0; y < linear.height; ++y)
    for (int x = 0; x < linear.width; ++x) {
      const Rgb c = linear.rgb(x, y);
      const bool red = red_where_positive && red_where_positive->at(x, y)[0] > 0;
      bgr.at<cv::Vec3b>(y, x) = red ? cv::Vec3b(0, 0, 255) : cv::Vec3b(byte_of(c[2]), byte_of(c[1]), byte_of(c[0]));
    }
  const int side = std::max(linear.width, linear.height);
  if (max_side_px > 0 && side > max_side_px) {
    const double s = double(max_side_px) / side;
    cv::Mat small;
    cv::resize(bgr, small, cv::Size(std::max(1, int(std::lround(linear.width * s))), std::max(1, int(std::lround(linear.height * s)))),
               0, 0, cv::INTER_AREA);
    bgr = small;
  }
  std::vector<uchar> png;
  cv::imencode(".png", bgr, png);
  return std::string(png.begin(), png.end());
}

}  // namespace insitu
