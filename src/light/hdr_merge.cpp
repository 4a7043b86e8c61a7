#include "light/hdr_merge.h"

#include <tbb/parallel_for.h>

#include <opencv2/photo.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>

#include "core/colour.h"
#include "core/error.h"

namespace insitu {

namespace {

cv::Mat to_8bit(const ImageFile& f) {
  if (f.bits != 8) throw InputError(f.path, "exposure brackets must be 8-bit images");
  const Image& img = f.stored;
  cv::Mat m(img.height, img.width, CV_8UC3);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c)
        m.at<cv::Vec3b>(y, x)[c] =
            static_cast<unsigned char>(std::lround(std::clamp(img.at(x, y)[c], 0.0f, 1.0f) * 255.0f));
  return m;
}

std::vector<cv::Mat> to_mats(const std::vector<ImageFile>& brackets) {
  std::vector<cv::Mat> mats;
  for (const auto& b : brackets) {
    if (b.stored.width != brackets[0].stored.width || b.stored.height != brackets[0].stored.height)
      throw InputError(b.path, fmt::format("bracket is {}x{}, the first ({}) is {}x{}", b.stored.width, b.stored.height,
                                           brackets[0].path, brackets[0].stored.width, brackets[0].stored.height));
    mats.push_back(to_8bit(b));
  }
  return mats;
}

constexpr int kSamples = 70;  // pixels CalibrateDebevec samples

std::vector<float> to_floats(const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); }

float mid_grey_linear() { return srgb_to_linear(128.0f / 255.0f); }

}  // namespace

ResponseCurve srgb_response() {
  ResponseCurve r;
  for (int c = 0; c < 3; ++c)
    for (int z = 0; z < 256; ++z) r.g[std::size_t(c)][std::size_t(z)] = srgb_to_linear(float(z) / 255.0f);
  return r;
}

// What CalibrateDebevec needs to determine g: its 70 sample pixels, and brackets that differ — an
// all-white (or all-equal) set of brackets says nothing about the response and would give
// non-finite curves.
void check_brackets_determine_a_response(const std::vector<ImageFile>& brackets, const std::vector<cv::Mat>& mats) {
  if (mats[0].rows * mats[0].cols < kSamples)
    throw InputError(brackets[0].path,
                     fmt::format("brackets of {}x{} pixels are too small to recover the camera response "
                                 "(at least {} pixels)",
                                 mats[0].cols, mats[0].rows, kSamples));
  std::array<bool, 256> seen{};
  int levels = 0;
  for (const cv::Mat& m : mats)
    for (auto it = m.begin<cv::Vec3b>(); it != m.end<cv::Vec3b>(); ++it)
      for (int c = 0; c < 3; ++c) {
        const unsigned char z = (*it)[c];
        if (z > 0 && z < 255 && !seen[z]) seen[z] = true, ++levels;
      }
  if (levels < 16)
    throw InputError(brackets[0].path,
                     fmt::format("the brackets hold {} unclipped grey level(s): too few to recover the camera "
                                 "response (every pixel clipped or black?)",
                                 levels));
}

ResponseCurve recover_response(const std::vector<ImageFile>& brackets, const std::vector<double>& exposures) {
  const std::vector<cv::Mat> mats = to_mats(brackets);
  check_brackets_determine_a_response(brackets, mats);
  cv::Mat response;
  try {
    cv::createCalibrateDebevec(kSamples, 10.0f, false)->process(mats, response, to_floats(exposures));
  } catch (const cv::Exception& e) {
    throw InputError(brackets[0].path, std::string("cannot recover the camera response from these brackets: ") + e.err);
  }
  ResponseCurve r;
  const float scale = mid_grey_linear();
  for (int z = 0; z < 256; ++z) {
    const cv::Vec3f v = response.at<cv::Vec3f>(z, 0);
    for (int c = 0; c < 3; ++c) r.g[std::size_t(c)][std::size_t(z)] = v[c] / response.at<cv::Vec3f>(128, 0)[c] * scale;
  }
  return r;
}

Image merge_brackets(const std::vector<ImageFile>& brackets, const std::vector<double>& exposures,
                     const ResponseCurve& r) {
  const std::vector<cv::Mat> mats = to_mats(brackets);
  // OpenCV wants g in its own scale (any constant factor passes through to the result).
  cv::Mat response(256, 1, CV_32FC3);
  for (int z = 0; z < 256; ++z)
    for (int c = 0; c < 3; ++c) response.at<cv::Vec3f>(z, 0)[c] = std::max(r.g[std::size_t(c)][std::size_t(z)], 1e-12f);
  cv::Mat hdr;
  try {
    cv::createMergeDebevec()->process(mats, hdr, to_floats(exposures), response);
  } catch (const cv::Exception& e) {
    throw InputError(brackets[0].path, std::string("cannot merge these brackets: ") + e.err);
  }
  const Image& first = brackets[0].stored;
  Image out(first.width, first.height, 3);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y)[c] = hdr.at<cv::Vec3f>(y, x)[c];
  sanitize(out);
  // A value clipped in the shortest bracket is clipped in all of them, and OpenCV's hat weight is 0
  // at 255: the merge gives 0 (or a value pulled down by the longer brackets) for the brightest
  // light of all. What is known there is a lower bound, X ≥ g(255)/k_min, which the shortest bracket
  // gives; such pixels get it (and are counted as clipped: clipped_fraction of the shortest).
  const std::size_t shortest = std::size_t(std::min_element(exposures.begin(), exposures.end()) - exposures.begin());
  const cv::Mat& s = mats[shortest];
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 3; ++c) {
        // OpenCV's Mat is BGR-agnostic here: we filled it in our channel order (to_8bit).
        if (s.at<cv::Vec3b>(y, x)[c] < 255) continue;
        const float bound = r.g[std::size_t(c)][255] / float(exposures[shortest]);
        out.at(x, y)[c] = std::max(out.at(x, y)[c], bound);
      }
  return out;
}

Image linearize_with_response(const ImageFile& file, const ResponseCurve& r) {
  if (file.bits != 8) throw InputError(file.path, "a recovered response applies to 8-bit images only");
  Image out(file.stored.width, file.stored.height, 3);
  // Rows in parallel: a 12-megapixel shot is 36 million lookups.
  const std::size_t row = std::size_t(out.width) * 3;
  tbb::parallel_for(std::size_t(0), std::size_t(out.height), [&](std::size_t y) {
    for (std::size_t i = y * row; i < (y + 1) * row; ++i) {
      const int z = int(std::lround(std::clamp(file.stored.data[i], 0.0f, 1.0f) * 255.0f));
      out.data[i] = r.g[i % 3][std::size_t(z)];
    }
  });
  return out;
}

namespace {
constexpr float kClipRampStart = 0.9f;

// The top of the stored range: a channel at or above it is clipped.
float clip_top(const ImageFile& file) { return file.bits == 8 ? 254.5f / 255.0f : 65534.5f / 65535.0f; }

// How clipped a pixel is: 0 below 0.9 of the range in every channel, rising linearly to 1 at the
// top of the stored range in its largest channel.
float degree_at(const Image& img, int x, int y, float top) {
  const float* p = img.at(x, y);
  return std::clamp((std::max({p[0], p[1], p[2]}) - kClipRampStart) / (top - kClipRampStart), 0.0f, 1.0f);
}

}  // namespace

Image clipped_degree(const ImageFile& file) {
  const Image& img = file.stored;
  Image degree(img.width, img.height, 1, 0.0f);
  if (!file.display_referred) return degree;
  const float top = clip_top(file);
  tbb::parallel_for(0, img.height, [&](int y) {
    for (int x = 0; x < img.width; ++x) *degree.at(x, y) = degree_at(img, x, y, top);
  });
  return degree;
}

// Where clipped_degree reaches 1, computed directly (no degree image: 48 MB at 12 megapixels).
Image clipped_mask(const ImageFile& file, int channels) {
  const Image& img = file.stored;
  Image mask(img.width, img.height, channels);
  if (!file.display_referred) return mask;
  const float top = clip_top(file);
  tbb::parallel_for(0, img.height, [&](int y) {
    for (int x = 0; x < img.width; ++x)
      if (degree_at(img, x, y, top) >= 1.0f) std::fill_n(mask.at(x, y), channels, 1.0f);
  });
  return mask;
}

double clipped_fraction(const Image& mask) {
  double clipped = 0;
  for (std::size_t i = 0; i < mask.data.size(); i += std::size_t(std::max(1, mask.channels))) clipped += mask.data[i];
  return clipped / std::max(1.0, double(mask.width) * mask.height);
}

double clipped_fraction(const ImageFile& file) { return clipped_fraction(clipped_mask(file)); }

}  // namespace insitu
