// A random radiance cube for sampling tests: 20% black texels, 5% of the rest 50× brighter.
#pragma once
#include <random>

#include "light/cubemap.h"

namespace insitu::test {

inline CubeMap random_cube(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, 1);
  CubeMap c(n);
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        c.set_texel(f, i, j, u(rng) < 0.2f ? Rgb(Rgb::Zero()) : Rgb(Rgb(u(rng), u(rng), u(rng)) * (u(rng) < 0.05f ? 50.0f : 1.0f)));
  c.update_borders();
  return c;
}

}  // namespace insitu::test
