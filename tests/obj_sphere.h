// A UV sphere written as an OBJ with the MTL text given, for the MTL tests (obj_materials_test.cpp)
// and the Cycles comparison of the export (blender_export_test.cpp).
#pragma once
#include <fmt/format.h>

#include <string>

#include "test_util.h"
#include "uv_sphere.h"

namespace insitu::test {

// `name`.obj and `name`.mtl in dir: the sphere (smooth normals, OBJ's UVs: v up), every face of
// material "m", whose statements are `mtl`. Returns the OBJ's path.
inline std::string write_obj_sphere(const TempDir& dir, const std::string& name, const Vec3f& centre, float radius,
                                    const std::string& mtl, int rings = 24) {
  const float c[3] = {centre.x(), centre.y(), centre.z()};
  const UvSphere s = make_uv_sphere(rings, 2 * rings, c, radius);
  std::string obj = fmt::format("mtllib {}.mtl\n", name);
  for (std::size_t i = 0; i < s.pos.size() / 3; ++i) {
    obj += fmt::format("v {} {} {}\nvn {} {} {}\n", s.pos[3 * i], s.pos[3 * i + 1], s.pos[3 * i + 2], s.nor[3 * i],
                       s.nor[3 * i + 1], s.nor[3 * i + 2]);
    obj += fmt::format("vt {} {}\n", s.uv[2 * i], 1.0f - s.uv[2 * i + 1]);
  }
  obj += "usemtl m\n";
  for (std::size_t i = 0; i < s.idx.size(); i += 3)
    obj += fmt::format("f {0}/{0}/{0} {1}/{1}/{1} {2}/{2}/{2}\n", s.idx[i] + 1, s.idx[i + 1] + 1, s.idx[i + 2] + 1);
  dir.write(name + ".mtl", "newmtl m\n" + mtl);
  return dir.write(name + ".obj", obj);
}

}  // namespace insitu::test
