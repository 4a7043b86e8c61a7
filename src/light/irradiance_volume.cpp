#include "light/irradiance_volume.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/sampler.h"
#include "core/stop.h"

namespace insitu {
namespace {

// L Y_lm / (p_room + p_uniform) added to the coefficients.
void accumulate(Sh9& acc, const Rgb& L, const Vec3f& dir, float pdf_room) {
  const float w = 1.0f / (pdf_room + 1.0f / (4 * kPiF));
  const auto Y = sh9_basis(dir.cast<double>());
  for (int k = 0; k < 9; ++k) acc.coeff[std::size_t(k)] += L * (float(Y[std::size_t(k)]) * w);
}

}  // namespace

Sh9 IrradianceVolume::project(const RoomLight& room, const Vec3f& p, int samples, std::uint64_t key) {
  Sh9 acc;
  for (Rgb& c : acc.coeff) c = Rgb::Zero();
  // Latin hypercube samples: each dimension stratified into `samples` strata, the strata of the
  // dimensions paired by permutations (Kensler 2013): a constant room comes out within 2.5 %.
  const std::uint32_t n = std::uint32_t(std::max(1, samples)), seed = std::uint32_t(key);
  auto stratum = [&](int k, int dim, float u) {
    return (float(permute(std::uint32_t(k), n, seed * 7u + std::uint32_t(dim))) + u) / float(n);
  };
  for (int k = 0; k < samples; ++k) {
    Sampler s(0x501E5ull, key, std::uint64_t(k));
    const float ue = stratum(k, 0, s.next()), us = stratum(k, 1, s.next()), ut = stratum(k, 2, s.next());
    const RoomSample rs = room.sample(p, ue, us, ut);
    if (rs.pdf > 0) accumulate(acc, rs.radiance, rs.dir, rs.pdf);
    // A uniform direction on the sphere.
    const float z = 1 - 2 * stratum(k, 3, s.next()), phi = 2 * kPiF * stratum(k, 4, s.next());
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    const Vec3f d(r * std::cos(phi), r * std::sin(phi), z);
    const RoomLookup l = room.lookup(p, d);
    accumulate(acc, l.radiance, d, l.pdf);
  }
  for (Rgb& c : acc.coeff) c /= float(std::max(1, samples));
  return acc;
}

IrradianceVolume::IrradianceVolume(const RoomLight& room, const RoomBox& box, int cells, int samples,
                                   const std::atomic<bool>* stop) {
  const Vec3f extent = box.max - box.min, slack = 1e-3f * extent;
  const float spacing = extent.maxCoeff() / float(std::max(1, cells));
  for (int a = 0; a < 3; ++a) n_[a] = std::max(2, int(std::ceil(extent[a] / spacing)) + 1);
  min_ = box.min + slack;
  step_ = (extent - 2 * slack).cwiseQuotient((n_ - Eigen::Vector3i::Ones()).cast<float>());
  probes_.resize(std::size_t(n_.prod()));
  tbb::parallel_for(0, n_.prod(), [&](int k) {
    throw_if_stopped(stop);
    const Eigen::Vector3i i(k % n_.x(), (k / n_.x()) % n_.y(), k / (n_.x() * n_.y()));
    probes_[std::size_t(k)] = project(room, min_ + i.cast<float>().cwiseProduct(step_), samples, std::uint64_t(k));
  });
}

Rgb IrradianceVolume::irradiance(const Vec3f& x, const Vec3f& n) const {
  // Trilinear weights of the 8 probes around x (clamped to the grid).
  const Vec3f g = (x - min_).cwiseQuotient(step_).cwiseMax(0.0f).cwiseMin((n_ - Eigen::Vector3i::Ones()).cast<float>());
  const Eigen::Vector3i i0 = g.cast<int>().cwiseMin(n_ - Eigen::Vector3i::Constant(2));
  const Vec3f f = g - i0.cast<float>();
  Sh9 sh;
  for (Rgb& c : sh.coeff) c = Rgb::Zero();
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3i d(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const float w = (d.x() ? f.x() : 1 - f.x()) * (d.y() ? f.y() : 1 - f.y()) * (d.z() ? f.z() : 1 - f.z());
    const Eigen::Vector3i i = i0 + d;
    const Sh9& p = probes_[std::size_t((i.z() * n_.y() + i.y()) * n_.x() + i.x())];
    for (int k = 0; k < 9; ++k) sh.coeff[std::size_t(k)] += w * p.coeff[std::size_t(k)];
  }
  return sh9_irradiance(sh, n).max(0.0f);
}

}  // namespace insitu
