// The room's prepared light and grids, shared by the renders of one room (light/room_cache.h).
#include <gtest/gtest.h>

#include <cmath>

#include "cube_fixture.h"
#include "light/room_cache.h"

namespace insitu {
namespace {

const RoomBox kRoom{Vec3f(-2.5f, 0, -3),
                    Vec3f(2.5f, 2.6f, 3),
                    Vec3f(-0.2f, 0.9f, -1.2f),
                    {{0, Vec3f(-2.5f, 0.9f, -2.2f), Vec3f(-2.5f, 2.1f, -0.6f)}},
                    std::nullopt};

// A grid asked for twice is built once; it is what a grid built on its own gives, bit for bit.
TEST(RoomCache, BuildsEachGridOnceAndAsItWouldAlone) {
  const CubeMap cube = test::random_cube(8, 3);
  RoomCache cache(cube, kRoom);
  const auto a = cache.plane(Vec3f::Zero(), Vec3f(0, 1, 0), 8);
  const auto b = cache.plane(Vec3f::Zero(), Vec3f(0, 1, 0), 8);
  EXPECT_EQ(a.get(), b.get());
  EXPECT_EQ(cache.light().get(), cache.light().get());
  const auto wall = cache.plane(kRoom.min, Vec3f(1, 0, 0), 8);
  EXPECT_NE(wall.get(), a.get());
  EXPECT_EQ(cache.plane_count(), 2u);
  const RoomLight room(cube, kRoom);
  const PlaneIrradiance alone(room, kRoom, Vec3f::Zero(), Vec3f(0, 1, 0), 8);
  for (const Vec3f& x : {Vec3f(0.3f, 0, -1.1f), Vec3f(-2.4f, 0, 2.9f), Vec3f(1.7f, 0, 0.4f)})
    EXPECT_TRUE((a->at(x) == alone.at(x)).all()) << x.transpose();
}

// A cache serves its own room only: another box, another cube or no box is not its.
TEST(RoomCache, ServesItsOwnRoomOnly) {
  const CubeMap cube = test::random_cube(8, 3), other = test::random_cube(8, 4);
  const RoomCache cache(cube, kRoom);
  EXPECT_TRUE(cache.serves(cube, kRoom));
  EXPECT_FALSE(cache.serves(other, kRoom));
  RoomBox moved = kRoom;
  moved.capture.x() += 0.01f;
  EXPECT_FALSE(cache.serves(cube, moved));
  RoomBox closed = kRoom;
  closed.openings.clear();
  EXPECT_FALSE(cache.serves(cube, closed));
  EXPECT_FALSE(cache.serves(cube, std::nullopt));
  EXPECT_TRUE(RoomCache(cube, std::nullopt).serves(cube, std::nullopt));
}

// Once its light is built the cache no longer holds the cube, and still tells its own from a cube
// that differs in one texel by one ulp.
TEST(RoomCache, ServesItsRoomAfterTheLightIsBuilt) {
  const CubeMap cube = test::random_cube(8, 3);
  RoomCache cache(cube, kRoom);
  ASSERT_NE(cache.light(), nullptr);
  EXPECT_TRUE(cache.serves(cube, kRoom));
  CubeMap nudged = cube;
  const Rgb v = cube.texel(2, 5, 6);
  nudged.set_texel(2, 5, 6, Rgb(std::nextafter(v[0], 1e9f), v[1], v[2]));
  nudged.update_borders();
  EXPECT_FALSE(nudged.same_texels(cube));
  EXPECT_FALSE(cache.serves(nudged, kRoom));
  EXPECT_NE(nudged.fingerprint(), cube.fingerprint());
  EXPECT_EQ(CubeMap(cube).fingerprint(), cube.fingerprint());
}

}  // namespace
}  // namespace insitu
