// Fuzz target: the image loader (OpenImageIO behind our header checks). The first byte picks the
// extension, which picks the reader: PNG, JPEG or OpenEXR.
#include "fuzz_common.h"
#include "core/image.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace insitu;
  if (size == 0) return 0;
  static const char* names[3] = {"i.png", "i.jpg", "i.exr"};
  return fuzz::run([&] { read_image_file(fuzz::write_input(names[data[0] % 3], data + 1, size - 1)); });
}
