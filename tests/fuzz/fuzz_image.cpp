// Fuzz target: the image loader (OpenImageIO behind our header checks). The first byte picks the
// extension, which picks the reader (PNG, JPEG or OpenEXR), and whether the file is read as an
// image or as a texture with its alpha (an 8-bit file's bytes kept).
#include "fuzz_common.h"
#include "core/image.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace insitu;
  if (size == 0) return 0;
  static const char* names[3] = {"i.png", "i.jpg", "i.exr"};
  return fuzz::run([&] {
    const std::string path = fuzz::write_input(names[data[0] % 3], data + 1, size - 1);
    data[0] & 4 ? void(read_texture_file(path, AlphaChannel::kKeep)) : void(read_image_file(path));
  });
}
