// What a room costs to prepare for the path integrator, kept for every render of that room: the
// room light (room_light.h: its samplers, built over the whole cube) and the irradiance grids of
// its planes (plane_irradiance.h: tens of thousands of Monte Carlo estimates). They depend on the
// cube and the room box alone, not on the objects, so a batch's entries that share a room
// (pipeline.h, load_scene's `room`) share one cache: the first entry builds them, the others start
// rendering at once, with bit for bit the same grids (each is a deterministic function of its key).
//
// A cache serves one room: it keeps its own copy of the cube and the box, and serves() tells
// whether a render's cube and box are those (the integrator checks before it uses one).
// Thread-safe; what it hands out is immutable and lives as long as its last holder.
#pragma once
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <tuple>

#include "light/plane_irradiance.h"

namespace insitu {

class RoomCache {
 public:
  RoomCache(const CubeMap& cube, std::optional<RoomBox> box);
  RoomCache(const RoomCache&) = delete;
  RoomCache& operator=(const RoomCache&) = delete;

  // The cube and the box are this cache's, bit for bit.
  bool serves(const CubeMap& cube, const std::optional<RoomBox>& box) const;
  // The room light of the cube and the box (built on the first call).
  std::shared_ptr<const RoomLight> light();
  // The grid over the plane through `point` with `normal` (PlaneIrradiance's arguments); needs a box.
  // A build that `stop` ends (core/stop.h) throws Stopped and stores nothing.
  std::shared_ptr<const PlaneIrradiance> plane(const Vec3f& point, const Vec3f& normal, int cells,
                                               const std::atomic<bool>* stop = nullptr);
  // Grids built so far (for the tests).
  std::size_t plane_count();

 private:
  using PlaneKey = std::tuple<float, float, float, float, float, float, int>;
  const std::unique_ptr<const CubeMap> cube_;  // RoomLight refers to it: its address must not move
  const std::optional<RoomBox> box_;
  std::mutex mutex_;
  std::shared_ptr<const RoomLight> light_;
  std::map<PlaneKey, std::shared_ptr<const PlaneIrradiance>> planes_;
};

}  // namespace insitu
