#include "output/image_compare.h"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <fmt/format.h>

#include "core/colour.h"

namespace insitu {

namespace {

cv::Mat display_luminance(const Image& img) {
  cv::Mat m(img.height, img.width, CV_64F);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const float* p = img.at(x, y);
      m.at<double>(y, x) = luminance(Rgb(linear_to_srgb(p[0]), linear_to_srgb(p[1]), linear_to_srgb(p[2])));
    }
  return m;
}

// The SSIM map (Wang et al. 2004, eq. 13) with Gaussian-weighted local statistics.
cv::Mat ssim_map(const cv::Mat& x, const cv::Mat& y) {
  const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  auto blur = [](const cv::Mat& m) {
    cv::Mat out;
    cv::GaussianBlur(m, out, cv::Size(11, 11), 1.5, 1.5, cv::BORDER_REFLECT);
    return out;
  };
  const cv::Mat mx = blur(x), my = blur(y);
  const cv::Mat sxx = blur(x.mul(x)) - mx.mul(mx), syy = blur(y.mul(y)) - my.mul(my), sxy = blur(x.mul(y)) - mx.mul(my);
  cv::Mat num = (2 * mx.mul(my) + c1).mul(2 * sxy + c2);
  cv::Mat den = (mx.mul(mx) + my.mul(my) + c1).mul(sxx + syy + c2);
  cv::Mat out;
  cv::divide(num, den, out);
  return out;
}

CompareNumbers numbers(const Image& a, const Image& b, const cv::Mat& ssim, const Image* mask) {
  CompareNumbers n;
  double se = 0, ref = 0, ssim_sum = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (mask) {
        bool inside = false;
        for (int c = 0; c < mask->channels; ++c) inside |= mask->at(x, y)[c] != 0.0f;
        if (!inside) continue;
      }
      ++n.pixels;
      ssim_sum += ssim.at<double>(y, x);
      for (int c = 0; c < 3; ++c) {
        const double d = double(a.at(x, y)[c]) - b.at(x, y)[c];
        se += d * d;
        ref += double(b.at(x, y)[c]) * b.at(x, y)[c];
        n.max_error = std::max(n.max_error, std::abs(d));
      }
    }
  if (n.pixels == 0) return n;
  const double count = double(n.pixels);
  n.rmse = std::sqrt(se / (3.0 * count));
  n.relative_rmse = ref > 0 ? n.rmse / std::sqrt(ref / (3.0 * count)) : (n.rmse > 0 ? INFINITY : 0.0);
  n.ssim = ssim_sum / count;
  return n;
}

}  // namespace

CompareResult compare_images(const Image& a, const Image& b, const Image* mask) {
  CompareResult r;
  const cv::Mat ssim = ssim_map(display_luminance(a), display_luminance(b));
  r.whole = numbers(a, b, ssim, nullptr);
  if (mask) r.masked = numbers(a, b, ssim, mask);
  r.error_luminance = Image(a.width, a.height, 1);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      *r.error_luminance.at(x, y) = std::abs(luminance(a.rgb(x, y)) - luminance(b.rgb(x, y)));
  return r;
}

Image comparison_picture(const Image& a, const Image& b, const CompareResult& r, const Image* a_display,
                         const Image* b_display) {
  const int w = a.width, h = a.height, bar = std::max(24, w / 16), gap = 4;
  const int total_w = 3 * w + 2 * gap + gap + bar + 90;
  cv::Mat canvas(std::max(h, 120), total_w, CV_8UC3, cv::Scalar(255, 255, 255));
  auto put = [&](const Image& img, const Image* display, int x0) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) {
          const float v = display ? std::clamp(display->at(x, y)[c], 0.0f, 1.0f) : linear_to_srgb(img.at(x, y)[c]);
          canvas.at<cv::Vec3b>(y, x0 + x)[2 - c] = static_cast<unsigned char>(std::lround(255 * v));
        }
  };
  put(a, a_display, 0);
  put(b, b_display, w + gap);
  // Heatmap of the error on 0 … max.
  float emax = 0;
  for (float v : r.error_luminance.data) emax = std::max(emax, v);
  cv::Mat e8(h, w, CV_8U);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      e8.at<unsigned char>(y, x) =
          static_cast<unsigned char>(emax > 0 ? std::lround(255 * *r.error_luminance.at(x, y) / emax) : 0);
  cv::Mat heat;
  cv::applyColorMap(e8, heat, cv::COLORMAP_INFERNO);
  heat.copyTo(canvas(cv::Rect(2 * (w + gap), 0, w, h)));
  // The colour bar: max at the top, 0 at the bottom, labelled.
  const int bx = 3 * w + 3 * gap;
  cv::Mat ramp(h, 1, CV_8U);
  for (int y = 0; y < h; ++y)
    ramp.at<unsigned char>(y, 0) = static_cast<unsigned char>(std::lround(255.0 * (h - 1 - y) / std::max(1, h - 1)));
  cv::Mat ramp_colour;
  cv::applyColorMap(ramp, ramp_colour, cv::COLORMAP_INFERNO);
  cv::resize(ramp_colour, ramp_colour, cv::Size(bar, h), 0, 0, cv::INTER_NEAREST);
  ramp_colour.copyTo(canvas(cv::Rect(bx, 0, bar, h)));
  cv::putText(canvas, fmt::format("{:.3g}", emax), cv::Point(bx + bar + 4, 14), cv::FONT_HERSHEY_SIMPLEX, 0.4,
              cv::Scalar(0, 0, 0), 1);
  cv::putText(canvas, "0", cv::Point(bx + bar + 4, h - 4), cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0), 1);
  cv::putText(canvas, "|dY|", cv::Point(bx + bar + 4, h / 2), cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0), 1);
  Image out(canvas.cols, canvas.rows, 3);
  for (int y = 0; y < canvas.rows; ++y)
    for (int x = 0; x < canvas.cols; ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y)[c] = canvas.at<cv::Vec3b>(y, x)[2 - c] / 255.0f;
  return out;
}

}  // namespace insitu
