// Handheld shots for the registration's tests and benchmark (light/shot_registration.h): six
// shots of an equirectangular world, each turned by a known misaim.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>

#include "light/cubemap.h"
#include "light/equirect.h"
#include "light/sixshot.h"

namespace insitu {
namespace test {

inline Mat3d rotation(const Vec3d& rotation_vector_rad) {
  const double angle = rotation_vector_rad.norm();
  if (angle == 0) return Mat3d::Identity();
  return Eigen::AngleAxisd(angle, rotation_vector_rad / angle).toRotationMatrix();
}

inline double angle_deg(const Mat3d& a, const Mat3d& b) {
  return rad_to_deg(Eigen::AngleAxisd(a * b.transpose()).angle());
}

// Six shots of `world` as a hand aims them: each turned by its true aim.
inline ShotSet handheld_shots(const Image& world, const std::array<Mat3d, 6>& aim, double hfov_deg, int w, int h) {
  ShotSet set;
  set.faced_face = kNegZ;
  set.set_hfov(hfov_deg);
  for (int s = 0; s < 6; ++s) {
    const ShotBasis b = shot_basis(s, kNegZ);
    const Mat3d& R = aim[std::size_t(s)];
    set.shots[std::size_t(s)] = render_shot([&](const Vec3f& d) { return equirect_lookup(world, d); },
                                            ShotBasis{R * b.forward, R * b.up, R * b.right}, hfov_deg, w, h);
    set.names[std::size_t(s)] = std::string("shot") + face_name(s);
  }
  return set;
}

// Misaims of σ = 2° per axis about random axes (roll included), their mean rotation vector taken out
// (the registration's prior fixes the shots' common rotation at the nominal one), or kept, as a hand
// leaves it.
inline std::array<Mat3d, 6> misaims(unsigned seed, bool mean_taken_out = true) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, deg_to_rad(2.0));
  std::array<Vec3d, 6> v;
  Vec3d mean = Vec3d::Zero();
  for (Vec3d& x : v) mean += (x = Vec3d(n(rng), n(rng), n(rng))) / 6;
  std::array<Mat3d, 6> R;
  if (!mean_taken_out) mean = Vec3d::Zero();
  for (int s = 0; s < 6; ++s) R[std::size_t(s)] = rotation(v[std::size_t(s)] - mean);
  return R;
}

// A room-sized world of features: an equirect of a dim gradient under 1500 rectangles of random
// size, colour and brightness (over two decades), whose corners SIFT finds.
inline Image feature_world(unsigned seed) {
  const int w = 1536, h = 768;
  Image img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.set_rgb(x, y, Rgb(0.2f, 0.2f, 0.25f) * (0.5f + float(y) / h));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> px(0, w - 1), py(0, h - 1), size(3, 36);
  std::uniform_real_distribution<float> u(0, 1);
  for (int k = 0; k < 1500; ++k) {
    const int x0 = px(rng), y0 = py(rng), sx = size(rng), sy = size(rng);
    const Rgb c = Rgb(0.4f + u(rng), 0.4f + u(rng), 0.4f + u(rng)) * std::pow(10.0f, 2 * u(rng) - 1);
    for (int y = y0; y < std::min(h, y0 + sy); ++y)
      for (int x = x0; x < x0 + sx; ++x) img.set_rgb(x % w, y, c);
  }
  return img;
}

// The mean relative luminance error of cube a against cube b, over every texel.
inline double mean_relative_error(const CubeMap& a, const CubeMap& b) {
  double err = 0, norm = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < a.size(); ++j)
      for (int i = 0; i < a.size(); ++i) {
        err += std::abs(luminance(a.texel(f, i, j)) - luminance(b.texel(f, i, j)));
        norm += luminance(b.texel(f, i, j));
      }
  return err / norm;
}

}  // namespace test
}  // namespace insitu
