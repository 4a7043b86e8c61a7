// What a room costs to prepare for the path integrator, kept for every render of that room: the
// room light (room_light.h: its samplers, built over the whole cube) and the irradiance grids of
// its planes (plane_irradiance.h: tens of thousands of Monte Carlo estimates). They depend on the
// cube and the room box alone, not on the objects, so a batch's entries that share a room
// (pipeline.h, load_scene's `room`) share one cache: the first entry builds them, the others start
// rendering at once, with bit for bit the same grids (each is a deterministic function of its key).
//
// A cache serves one room: it keeps the cube's fingerprint and the box, and serves() tells
// whether a render's cube and box are those (the integrator checks before it uses one). Its copy
// of the cube lives until the room light is built from it (the light keeps what it needs): at a
// 1024 face that is 76 MB less while rendering.
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

  // The cube and the box are this cache's (the box bit for bit, the cube by its fingerprint).
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
  std::unique_ptr<const CubeMap> cube_;  // until light_ is built
  const int cube_size_;
  const std::uint64_t cube_fingerprint_;
  const std::optional<RoomBox> box_;
  std::mutex mutex_;
  std::shared_ptr<const RoomLight> light_;
  std::map<PlaneKey, std::shared_ptr<const PlaneIrradiance>> planes_;
};

}  // namespace insitu
