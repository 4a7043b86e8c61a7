#include "light/irradiance_at.h"

#include <stdexcept>

#include "light/irradiance_volume.h"

namespace insitu {
namespace {

class ByNormal final : public IrradianceAt {
 public:
  explicit ByNormal(std::unique_ptr<IrradianceField> field) : field_(std::move(field)) {}
  Rgb irradiance(const Vec3f&, const Vec3f& n) const override { return field_->irradiance(n); }

 private:
  std::unique_ptr<IrradianceField> field_;
};

// The room's light and the probes projected from it (the volume refers to the light only while it
// is built; it is kept for the volume's lifetime all the same, as the integrator kept it).
class ByPosition final : public IrradianceAt {
 public:
  ByPosition(const CubeMap& radiance, const RoomBox& room, const std::atomic<bool>* stop)
      : room_(std::make_unique<RoomLight>(radiance, room)), volume_(*room_, room, 8, 2048, stop) {}
  Rgb irradiance(const Vec3f& x, const Vec3f& n) const override { return volume_.irradiance(x, n); }

 private:
  std::unique_ptr<RoomLight> room_;
  IrradianceVolume volume_;
};

}  // namespace

std::unique_ptr<IrradianceAt> make_irradiance_at(IrradianceMode mode, const CubeMap& radiance,
                                                 const std::optional<RoomBox>& room, int exact_size,
                                                 const std::atomic<bool>* stop) {
  if (is_directional(mode)) return std::make_unique<ByNormal>(make_irradiance(mode, radiance, exact_size, stop));
  if (!room) throw std::invalid_argument("the volume irradiance mode needs environment.room_box");
  return std::make_unique<ByPosition>(radiance, *room, stop);
}

}  // namespace insitu
