#include "light/plane_irradiance.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/sampler.h"
#include "core/sampling.h"
#include "core/stop.h"

namespace insitu {

Rgb PlaneIrradiance::estimate(const RoomLight& room, const Vec3f& x, const Vec3f& n, int samples, std::uint64_t key) {
  Rgb sum = Rgb::Zero();
  for (int k = 0; k < samples; ++k) {
    Sampler s(0x1AAD1A4CEull, key, std::uint64_t(k));
    const float ue = s.next(), us = s.next(), ut = s.next();
    const RoomSample rs = room.sample(x, ue, us, ut);
    const float cos_l = n.dot(rs.dir);
    if (rs.pdf > 0 && cos_l > 0) sum += rs.radiance * (cos_l / rs.pdf * power_heuristic(rs.pdf, cos_l / kPiF));
    const Vec3f wi = cosine_sample(n, s.next(), s.next());
    const float pdf_b = n.dot(wi) / kPiF;
    if (pdf_b > 0) {
      const RoomLookup l = room.lookup(x, wi);
      sum += kPiF * l.radiance * power_heuristic(pdf_b, l.pdf);
    }
  }
  return sum / float(std::max(1, samples));
}

PlaneIrradiance::PlaneIrradiance(const RoomLight& room, const RoomBox& box, const Vec3f& point, const Vec3f& normal,
                                 int cells, int samples, const std::atomic<bool>* stop)
    : normal_(normal.normalized()) {
  u_ = (std::abs(normal_.x()) < 0.9f ? Vec3f(1, 0, 0) : Vec3f(0, 1, 0)).cross(normal_).normalized();
  v_ = normal_.cross(u_);
  // The box's corners projected onto the plane bound the grid.
  Vec2f lo = Vec2f::Constant(INFINITY), hi = Vec2f::Constant(-INFINITY);
  for (int c = 0; c < 8; ++c) {
    const Vec3f corner((c & 1 ? box.max : box.min).x(), (c & 2 ? box.max : box.min).y(),
                       (c & 4 ? box.max : box.min).z());
    const Vec2f st((corner - point).dot(u_), (corner - point).dot(v_));
    lo = lo.cwiseMin(st), hi = hi.cwiseMax(st);
  }
  cell_ = std::max(hi.x() - lo.x(), hi.y() - lo.y()) / float(std::max(1, cells));
  nu_ = int(std::ceil((hi.x() - lo.x()) / cell_)) + 1;
  nv_ = int(std::ceil((hi.y() - lo.y()) / cell_)) + 1;
  origin_ = point + lo.x() * u_ + lo.y() * v_;
  u_ *= cell_, v_ *= cell_;
  nodes_.assign(std::size_t(nu_) * nv_, Rgb::Zero());
  // Nodes a little above the plane, pulled inside the box (a node on its face sees it edge-on).
  const Vec3f slack = 1e-4f * (box.max - box.min), lift = 1e-4f * (box.max - box.min).maxCoeff() * normal_;
  tbb::parallel_for(0, nv_, [&](int j) {
    throw_if_stopped(stop);
    for (int i = 0; i < nu_; ++i) {
      const Vec3f x =
          (origin_ + float(i) * u_ + float(j) * v_ + lift).cwiseMax(box.min + slack).cwiseMin(box.max - slack);
      nodes_[std::size_t(j) * nu_ + i] = estimate(room, x, normal_, samples, std::uint64_t(j) * nu_ + i);
    }
  });
}

Rgb PlaneIrradiance::at(const Vec3f& x) const {
  const Vec3f d = x - origin_;
  const float s = std::clamp(d.dot(u_) / (cell_ * cell_), 0.0f, float(nu_ - 1));
  const float t = std::clamp(d.dot(v_) / (cell_ * cell_), 0.0f, float(nv_ - 1));
  const int i = std::min(int(s), nu_ - 2 < 0 ? 0 : nu_ - 2), j = std::min(int(t), nv_ - 2 < 0 ? 0 : nv_ - 2);
  const float a = std::min(1.0f, s - float(i)), b = std::min(1.0f, t - float(j));
  auto node = [&](int ii, int jj) { return nodes_[std::size_t(std::min(jj, nv_ - 1)) * nu_ + std::min(ii, nu_ - 1)]; };
  return (1 - b) * ((1 - a) * node(i, j) + a * node(i + 1, j)) +
         b * ((1 - a) * node(i, j + 1) + a * node(i + 1, j + 1));
}

}  // namespace insitu
