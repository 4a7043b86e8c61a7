#include "light/room_cache.h"

#include <stdexcept>

namespace insitu {

RoomCache::RoomCache(const CubeMap& cube, std::optional<RoomBox> box)
    : cube_(std::make_unique<const CubeMap>(cube)),
      cube_size_(cube.size()),
      cube_fingerprint_(cube.fingerprint()),
      box_(std::move(box)) {}

namespace {
bool same_box(const RoomBox& a, const RoomBox& b) {
  if (a.min != b.min || a.max != b.max || a.capture != b.capture || a.openings.size() != b.openings.size())
    return false;
  for (std::size_t k = 0; k < a.openings.size(); ++k)
    if (a.openings[k].axis != b.openings[k].axis || a.openings[k].min != b.openings[k].min ||
        a.openings[k].max != b.openings[k].max)
      return false;
  return true;
}
}  // namespace

bool RoomCache::serves(const CubeMap& cube, const std::optional<RoomBox>& box) const {
  if (box.has_value() != box_.has_value() || (box && !same_box(*box, *box_))) return false;
  return cube.size() == cube_size_ && cube.fingerprint() == cube_fingerprint_;
}

std::shared_ptr<const RoomLight> RoomCache::light() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!light_) {
    light_ = std::make_shared<const RoomLight>(*cube_, box_);
    cube_.reset();
  }
  return light_;
}

// Built outside the lock (the grids run in parallel); two threads asking for the same new grid
// at once both build it, and the first one stored is kept: they are equal.
std::shared_ptr<const PlaneIrradiance> RoomCache::plane(const Vec3f& point, const Vec3f& normal, int cells,
                                                        const std::atomic<bool>* stop) {
  if (!box_) throw std::logic_error("RoomCache::plane without a room box");
  const PlaneKey key{point.x(), point.y(), point.z(), normal.x(), normal.y(), normal.z(), cells};
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (const auto it = planes_.find(key); it != planes_.end()) return it->second;
  }
  const std::shared_ptr<const RoomLight> room = light();
  auto grid = std::make_shared<const PlaneIrradiance>(*room, *box_, point, normal, cells, 256, stop);
  const std::lock_guard<std::mutex> lock(mutex_);
  return planes_.emplace(key, std::move(grid)).first->second;
}

std::size_t RoomCache::plane_count() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return planes_.size();
}

}  // namespace insitu
