// Radiance cubes for tests: a random one for sampling tests, a constant one, a dim sky with a sun.
#pragma once
#include <random>

#include "light/cubemap.h"

namespace insitu::test {

// 20% black texels, 5% of the rest 50× brighter.
inline CubeMap random_cube(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, 1);
  CubeMap c(n);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        c.set_texel(
            f, i, j,
            u(rng) < 0.2f ? Rgb(Rgb::Zero()) : Rgb(Rgb(u(rng), u(rng), u(rng)) * (u(rng) < 0.05f ? 50.0f : 1.0f)));
  c.update_borders();
  return c;
}

// Every texel `value`.
inline CubeMap constant_cube(int n, const Rgb& value) {
  CubeMap c(n);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) c.set_texel(f, i, j, value);
  c.update_borders();
  return c;
}

// Every texel `sky`, and the one texel holding the direction to_sun `sun`.
inline CubeMap sun_cube(int n, const Vec3f& to_sun, float sky, float sun) {
  CubeMap c(n);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) c.set_texel(f, i, j, Rgb::Constant(sky));
  const FaceCoord fc = direction_to_face(to_sun);
  c.set_texel(fc.face, int(fc.s * float(n)), int(fc.t * float(n)), Rgb::Constant(sun));
  c.update_borders();
  return c;
}

}  // namespace insitu::test
