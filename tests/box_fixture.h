// A closed axis-aligned box of half-size `scale` centred at `centre` (default the origin), Lambertian with the given Kd
// ("r g b"), written to a temporary folder and loaded as the objects' Embree scene: the convex
// object of the furnace and closed-surface tests.
#pragma once
#include <string>
#include <vector>

#include "render/embree_scene.h"
#include "render/mesh.h"
#include "scene/scene_file.h"
#include "test_util.h"

namespace insitu::test {

inline EmbreeScene make_box(const TempDir& dir, const std::string& kd, double scale,
                            const Vec3d& centre = Vec3d::Zero()) {
  dir.write("box.mtl", "newmtl m\nKd " + kd + "\n");
  const std::string obj =
      "mtllib box.mtl\nusemtl m\n"
      "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
      "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";
  Warnings w;
  std::vector<Mesh> meshes;
  meshes.push_back(load_obj(dir.write("box.obj", obj), w));
  transform_mesh(meshes.back(), object_transform(centre, 0, {0, 1, 0}, Vec3d::Constant(scale)));
  return EmbreeScene(std::move(meshes));
}

}  // namespace insitu::test
