#include "light/plane_grid.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/stop.h"

namespace insitu {

PlaneGrid::PlaneGrid(const RoomBox& box, const Vec3f& point, const Vec3f& normal, int cells)
    : normal_(normal.normalized()), box_min_(box.min), box_max_(box.max) {
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
  values_.assign(std::size_t(nu_) * nv_, Rgb::Zero());
  slack_ = 1e-4f * (box.max - box.min), lift_ = 1e-4f * (box.max - box.min).maxCoeff() * normal_;
}

void PlaneGrid::fill(const std::function<Rgb(const Vec3f&, std::uint64_t)>& value, const std::atomic<bool>* stop) {
  tbb::parallel_for(0, nv_, [&](int j) {
    throw_if_stopped(stop);
    for (int i = 0; i < nu_; ++i) {
      const Vec3f x =
          (origin_ + float(i) * u_ + float(j) * v_ + lift_).cwiseMax(box_min_ + slack_).cwiseMin(box_max_ - slack_);
      values_[std::size_t(j) * nu_ + i] = value(x, std::uint64_t(j) * nu_ + i);
    }
  });
}

Rgb PlaneGrid::at(const Vec3f& x) const {
  const Vec3f d = x - origin_;
  const float s = std::clamp(d.dot(u_) / (cell_ * cell_), 0.0f, float(nu_ - 1));
  const float t = std::clamp(d.dot(v_) / (cell_ * cell_), 0.0f, float(nv_ - 1));
  const int i = std::min(int(s), nu_ - 2 < 0 ? 0 : nu_ - 2), j = std::min(int(t), nv_ - 2 < 0 ? 0 : nv_ - 2);
  const float a = std::min(1.0f, s - float(i)), b = std::min(1.0f, t - float(j));
  auto node = [&](int ii, int jj) { return values_[std::size_t(std::min(jj, nv_ - 1)) * nu_ + std::min(ii, nu_ - 1)]; };
  return (1 - b) * ((1 - a) * node(i, j) + a * node(i + 1, j)) +
         b * ((1 - a) * node(i, j + 1) + a * node(i + 1, j + 1));
}

}  // namespace insitu
