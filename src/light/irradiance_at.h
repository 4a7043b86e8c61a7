// Every irradiance mode behind one factory, as a field of position and normal: E(x, n). The
// directional modes (light/irradiance.h: gaussian, sh9, exact) look the cube up by the normal and
// ignore x; `volume` (irradiance_volume.h) interpolates its probes at x, and so needs the room box
// (std::invalid_argument without one: the scene loader refuses that case first, with the place).
// `stop`: core/stop.h, during the precomputation.
#pragma once
#include <atomic>
#include <memory>
#include <optional>

#include "light/irradiance.h"
#include "light/room_light.h"

namespace insitu {

class IrradianceAt {
 public:
  virtual ~IrradianceAt() = default;
  virtual Rgb irradiance(const Vec3f& x_world, const Vec3f& normal_unit) const = 0;
};

std::unique_ptr<IrradianceAt> make_irradiance_at(IrradianceMode mode, const CubeMap& radiance,
                                                 const std::optional<RoomBox>& room, int exact_size = 32,
                                                 const std::atomic<bool>* stop = nullptr);

}  // namespace insitu
