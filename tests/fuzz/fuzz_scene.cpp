// Fuzz target: the scene parser (JSON with JSON paths in every error). The folder holds a photo
// and a mesh, so that inputs may get past the file checks.
#include "fuzz_common.h"
#include "scene/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace insitu;
  return fuzz::run([&] { parse_scene_file(fuzz::write_input("scene.json", data, size)); });
}
