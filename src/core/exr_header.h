// The size an OpenEXR file declares, read from its header alone (OpenEXRCore's C API).
//
// OpenEXR's C++ reader, which OpenImageIO opens an EXR with, allocates its line buffers (a row's
// bytes × lines per chunk, for several threads) while opening the file: a 678-byte file whose
// header declares 8 million pixels per row makes it reserve gigabytes before insitu can see the
// header and refuse it (image.h: the decompression-bomb check). Reading the header with
// OpenEXRCore first allocates nothing of the sort.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

namespace insitu {

// Width and height of the largest part's data window; nothing when the file is not an OpenEXR
// file or its header cannot be read (the image reader then says why).
std::optional<std::pair<std::int64_t, std::int64_t>> exr_declared_size(const std::string& path);

}  // namespace insitu
