// Fuzz target: the glTF reader (tinygltf's parser, Draco's and meshoptimizer's decoders, then
// insitu's checks of the accessors, nodes and materials). The first byte chooses whether the input
// is a .gltf (JSON, buffers as data URIs) or a .glb. The seeds sphere_draco.glb and
// sphere_meshopt.glb are tests/gltf_compression_test.cpp's spheres.
#include "fuzz_common.h"
#include "render/gltf_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace insitu;
  if (size == 0) return 0;
  return fuzz::run([&] {
    Warnings w;
    load_gltf(fuzz::write_input(data[0] & 1 ? "x.glb" : "x.gltf", data + 1, size - 1), w);
  });
}
