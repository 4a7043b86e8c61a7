// A stop asked for during loading and an integrator's preparation (core/stop.h): each long step
// ends with Stopped once the flag is set, and a cache keeps nothing of a step that was stopped.
// Inverse lighting's own stops are tested beside it (inverse_lighting_test.cpp,
// inverse_lighting_solve_test.cpp); the studio's, end to end, in studio_render_test.cpp.
#include <gtest/gtest.h>

#include <atomic>

#include "core/stop.h"
#include "cube_fixture.h"
#include "integrators/registry.h"
#include "light/irradiance.h"
#include "render/embree_scene.h"
#include "light/irradiance_volume.h"
#include "light/room_cache.h"
#include "scene/pipeline.h"
#include "scene_fixture.h"

namespace insitu {
namespace {

const RoomBox kRoom{Vec3f(-2.5f, 0, -3), Vec3f(2.5f, 2.6f, 3), Vec3f(-0.2f, 0.9f, -1.2f), {}, std::nullopt};
const std::atomic<bool> kStop{true}, kGo{false};

TEST(Stop, TheIrradianceGridsEndWhenAsked) {
  const CubeMap cube = test::random_cube(8, 3);
  EXPECT_THROW(exact_irradiance_cube(cube, 8, 512, &kStop), Stopped);
  EXPECT_THROW(make_irradiance(IrradianceMode::kExact, cube, 8, &kStop), Stopped);
  const RoomLight room(cube, kRoom);
  EXPECT_THROW(PlaneIrradiance(room, kRoom, Vec3f::Zero(), Vec3f(0, 1, 0), 8, 16, &kStop), Stopped);
  EXPECT_THROW(IrradianceVolume(room, kRoom, 2, 16, &kStop), Stopped);
  // Not asked: the same work runs to its end.
  EXPECT_NO_THROW(exact_irradiance_cube(cube, 8, 512, &kGo));
  EXPECT_NO_THROW(IrradianceVolume(room, kRoom, 2, 16, &kGo));
}

TEST(Stop, ARoomCacheKeepsNoGridThatWasStopped) {
  const CubeMap cube = test::random_cube(8, 3);
  RoomCache cache(cube, kRoom);
  EXPECT_THROW(cache.plane(Vec3f::Zero(), Vec3f(0, 1, 0), 8, &kStop), Stopped);
  EXPECT_EQ(cache.plane_count(), 0u);
  const auto grid = cache.plane(Vec3f::Zero(), Vec3f(0, 1, 0), 8, &kGo);
  EXPECT_EQ(cache.plane_count(), 1u);
  const RoomLight room(cube, kRoom);
  const PlaneIrradiance alone(room, kRoom, Vec3f::Zero(), Vec3f(0, 1, 0), 8);
  EXPECT_TRUE((grid->at(Vec3f(0.3f, 0, -1.1f)) == alone.at(Vec3f(0.3f, 0, -1.1f))).all());
}

// Every integrator whose preparation takes time stops in it: path (the room light and the planes'
// grids), irradiance (the exact cube, or the volume's probes).
TEST(Stop, TheIntegratorsStopInTheirPreparation) {
  const CubeMap cube = test::random_cube(8, 3);
  const EmbreeScene objects(std::vector<Mesh>{});
  RenderInputs in;
  in.objects = &objects;
  in.environment = &cube;
  in.room = kRoom;
  in.stop = &kStop;
  EXPECT_THROW(make_integrator("path", in, json::object()), Stopped);
  EXPECT_THROW(make_integrator("irradiance", in, {{"irradiance", "exact"}}), Stopped);
  EXPECT_THROW(make_integrator("irradiance", in, {{"irradiance", "volume"}}), Stopped);
  in.stop = &kGo;
  EXPECT_NE(make_integrator("path", in, json::object()), nullptr);
}

TEST(Stop, LoadingEndsWhenAsked) {
  test::SceneFixture fx;
  const SceneSpec spec = parse_scene_file(fx.write());
  EXPECT_THROW(load_scene(spec, {}, nullptr, &kStop), Stopped);
  EXPECT_NO_THROW(load_scene(spec, {}, nullptr, &kGo));
}

}  // namespace
}  // namespace insitu
