// Fuzz target: the OBJ reader (the validation pass with file:line, then tinyobjloader). The first
// byte chooses whether the input is the OBJ or its MTL (then with a fixed OBJ that names it).
#include "fuzz_common.h"
#include "render/mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace insitu;
  if (size == 0) return 0;
  return fuzz::run([&] {
    Warnings w;
    if (data[0] & 1) {
      fuzz::write_input("m.mtl", data + 1, size - 1);
      const char obj[] = "mtllib m.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n";
      load_obj(fuzz::write_input("m.obj", reinterpret_cast<const std::uint8_t*>(obj), sizeof(obj) - 1), w);
    } else {
      load_obj(fuzz::write_input("x.obj", data + 1, size - 1), w);
    }
  });
}
