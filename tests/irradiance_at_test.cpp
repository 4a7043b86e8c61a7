// Every irradiance mode behind one factory (light/irradiance_at.h): the directional modes are
// make_irradiance's field wherever x is, the volume is its probes' interpolation, and a volume
// without a room box is refused.
#include <gtest/gtest.h>

#include <stdexcept>

#include "cube_fixture.h"
#include "light/irradiance_at.h"
#include "light/irradiance_volume.h"

namespace insitu {
namespace {

const RoomBox kRoom{Vec3f(-2.5f, 0, -3), Vec3f(2.5f, 2.6f, 3), Vec3f(-0.2f, 0.9f, -1.2f), {}, std::nullopt};

TEST(IrradianceAt, EveryModeFromOneFactory) {
  const CubeMap cube = test::random_cube(8, 3);
  const std::vector<Vec3f> points = {Vec3f(0, 0.5f, 0), Vec3f(-2, 2, 2.5f)};
  const Vec3f n = Vec3f(0.3f, 1, -0.2f).normalized();
  for (IrradianceMode mode : directional_irradiance_modes()) {
    const auto at = make_irradiance_at(mode, cube, std::nullopt, 8);
    const auto field = make_irradiance(mode, cube, 8);
    for (const Vec3f& x : points)
      EXPECT_TRUE((at->irradiance(x, n) == field->irradiance(n)).all()) << irradiance_mode_name(mode);
  }
  const auto volume = make_irradiance_at(IrradianceMode::kVolume, cube, kRoom, 8);
  const RoomLight room(cube, kRoom);
  const IrradianceVolume probes(room, kRoom);
  for (const Vec3f& x : points)
    EXPECT_TRUE((volume->irradiance(x, n) == probes.irradiance(x, n)).all()) << x.transpose();
  EXPECT_FALSE((volume->irradiance(points[0], n) == volume->irradiance(points[1], n)).all()) << "the volume ignores x";
  EXPECT_THROW(make_irradiance_at(IrradianceMode::kVolume, cube, std::nullopt), std::invalid_argument);
}

}  // namespace
}  // namespace insitu
