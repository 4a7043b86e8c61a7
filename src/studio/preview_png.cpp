#include "studio/preview_png.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/colour.h"

namespace insitu {

namespace {

// Rounded half up, as OpenImageIO converts float to 8 bits, so that an image here is the CLI's
// PNG byte for byte (cv::saturate_cast rounds half to even).
uchar encoded_byte(float v) { return v > 0 ? uchar(std::floor(255 * std::min(v, 1.0f) + 0.5f)) : 0; }  // NaN: 0
uchar byte_of(float linear) { return encoded_byte(linear_to_srgb(std::clamp(linear, 0.0f, 1.0f))); }

std::string png_of(const cv::Mat& bgr) {
  std::vector<uchar> png;
  cv::imencode(".png", bgr, png);
  return std::string(png.begin(), png.end());
}

}  // namespace

std::string display_png(const Image& encoded) {
  cv::Mat bgr(encoded.height, encoded.width, CV_8UC3);
  for (int y = 0; y < encoded.height; ++y)
    for (int x = 0; x < encoded.width; ++x) {
      const float* p = encoded.at(x, y);
      const float r = p[0], g = encoded.channels >= 3 ? p[1] : r, b = encoded.channels >= 3 ? p[2] : r;
      bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(encoded_byte(b), encoded_byte(g), encoded_byte(r));
    }
  return png_of(bgr);
}

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
    cv::resize(
        bgr, small,
        cv::Size(std::max(1, int(std::lround(linear.width * s))), std::max(1, int(std::lround(linear.height * s)))), 0,
        0, cv::INTER_AREA);
    bgr = small;
  }
  return png_of(bgr);
}

}  // namespace insitu
