// What an OpenEXR file declares, read from its header alone (OpenEXRCore's C API).
//
// OpenEXR's C++ reader, which OpenImageIO opens an EXR with, allocates its line buffers while
// opening the file: (a row's bytes over all channels × rows per chunk), or a tile's bytes, for
// several threads. A 678-byte file whose header declares 8 million pixels per row, or thousands
// of bytes per pixel, makes it reserve gigabytes before insitu can see the header and refuse it
// (image.h: the decompression-bomb and chunk checks). Reading the header with OpenEXRCore first
// allocates nothing of the sort.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

namespace insitu {

struct ExrLayout {
  // The part with the most declared bytes: its data window (0 × 0 when the window is empty).
  std::int64_t width = 0, height = 0;
  // Bytes per pixel over all its channels as stored (HALF 2, FLOAT and UINT 4). Subsampled
  // channels are counted at full resolution: an upper bound.
  std::int64_t bytes_per_pixel = 0;
  // The largest chunk of any part, as OpenEXR's reader sizes its buffers: a row's bytes × the
  // compression's rows per chunk (1 to 256), or a tile's bytes. In double: a header may declare
  // 2^32 × 256 × thousands of bytes, beyond 64-bit integers.
  double chunk_bytes = 0;

  double decoded_bytes() const { return double(width) * double(height) * double(bytes_per_pixel); }
};

// Nothing when the file is not an OpenEXR file (no magic number). A file with the magic number
// whose header OpenEXRCore cannot parse is refused (InputError naming the file): the C++ reader is
// more lenient and allocates what such a header declares (a fuzzer's mutant of the 64-megapixel
// bomb whose Core header failed to parse passed unchecked and took 11 s under the sanitizers).
std::optional<ExrLayout> exr_declared_layout(const std::string& path);

}  // namespace insitu
