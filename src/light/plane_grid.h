// Values at the nodes of a square grid over a plane's part inside the room box, read by bilinear
// interpolation: the room's irradiance over a real surface (plane_irradiance.h) and the change the
// objects make there (the path integrator's change grid). Nodes are `cells` to the box's larger
// extent on the plane apart, each a little above the plane and pulled inside the box (a node on a
// box face would see it edge-on).
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "light/room_light.h"

namespace insitu {

class PlaneGrid {
 public:
  PlaneGrid() = default;
  PlaneGrid(const RoomBox& box, const Vec3f& point, const Vec3f& normal, int cells);
  // value(x, key) at every node x (key: the node's index, for its random numbers), rows in
  // parallel; `stop` (core/stop.h) is looked at before each row.
  void fill(const std::function<Rgb(const Vec3f& x, std::uint64_t key)>& value, const std::atomic<bool>* stop);
  Rgb at(const Vec3f& x) const;  // bilinear; clamped to the grid
  const Vec3f& normal() const { return normal_; }
  std::size_t nodes() const { return values_.size(); }

 private:
  Vec3f origin_ = Vec3f::Zero(), u_ = Vec3f::Zero(), v_ = Vec3f::Zero(), normal_ = Vec3f::UnitY();
  Vec3f slack_ = Vec3f::Zero(), lift_ = Vec3f::Zero(), box_min_ = Vec3f::Zero(), box_max_ = Vec3f::Zero();
  float cell_ = 1;
  int nu_ = 0, nv_ = 0;  // nodes along u and v
  std::vector<Rgb> values_;
};

}  // namespace insitu
