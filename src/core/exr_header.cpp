#include "core/exr_header.h"

#include <OpenEXR/openexr.h>

#include <algorithm>
#include <fstream>

#include "core/error.h"

namespace insitu {

namespace {
// Keeps OpenEXRCore's last message (in the context's user data) instead of printing it.
void keep_message(exr_const_context_t ctx, exr_result_t, const char* message) {
  void* user = nullptr;
  if (exr_get_user_data(ctx, &user) == EXR_ERR_SUCCESS && user && message) *static_cast<std::string*>(user) = message;
}

bool has_exr_magic(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char magic[4] = {0, 0, 0, 0};
  in.read(reinterpret_cast<char*>(magic), 4);
  return in && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01;
}

std::int64_t bytes_per_pixel(exr_const_context_t ctx, int part) {
  const exr_attr_chlist_t* channels = nullptr;
  if (exr_get_channels(ctx, part, &channels) != EXR_ERR_SUCCESS || !channels) return 0;
  std::int64_t bytes = 0;
  for (int c = 0; c < channels->num_channels; ++c) bytes += channels->entries[c].pixel_type == EXR_PIXEL_HALF ? 2 : 4;
  return bytes;
}

// Rows × columns of one chunk: the data window's width × rows per chunk for scanline parts, the
// tile for tiled ones (OpenEXR sizes a tile's buffer by the tile, whatever the data window).
double chunk_pixels(exr_const_context_t ctx, int part, std::int64_t width) {
  exr_storage_t storage = EXR_STORAGE_SCANLINE;
  if (exr_get_storage(ctx, part, &storage) != EXR_ERR_SUCCESS) return 0;
  if (storage == EXR_STORAGE_TILED || storage == EXR_STORAGE_DEEP_TILED) {
    std::uint32_t x = 0, y = 0;
    exr_tile_level_mode_t level;
    exr_tile_round_mode_t round;
    if (exr_get_tile_descriptor(ctx, part, &x, &y, &level, &round) != EXR_ERR_SUCCESS) return 0;
    return double(x) * double(y);
  }
  std::int32_t rows = 0;
  if (exr_get_scanlines_per_chunk(ctx, part, &rows) != EXR_ERR_SUCCESS) return 0;
  return double(width) * std::max(rows, 1);
}
}  // namespace

std::optional<ExrLayout> exr_declared_layout(const std::string& path) {
  if (!has_exr_magic(path)) return std::nullopt;
  std::string message;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = keep_message;
  init.user_data = &message;
  init.flags |= EXR_CONTEXT_FLAG_STRICT_HEADER;
  exr_context_t ctx = nullptr;
  std::optional<ExrLayout> layout;
  int parts = 0;
  if (exr_start_read(&ctx, path.c_str(), &init) != EXR_ERR_SUCCESS || exr_get_count(ctx, &parts) != EXR_ERR_SUCCESS) {
    exr_finish(&ctx);
    std::replace(message.begin(), message.end(), '\n', ' ');
    throw InputError(path, "cannot read the OpenEXR header: " + (message.empty() ? std::string("corrupt") : message));
  }
  for (int p = 0; p < parts; ++p) {
    exr_attr_box2i_t dw;
    if (exr_get_data_window(ctx, p, &dw) != EXR_ERR_SUCCESS) continue;
    ExrLayout part;
    part.width = std::max<std::int64_t>(0, std::int64_t(dw.max.x) - dw.min.x + 1);
    part.height = std::max<std::int64_t>(0, std::int64_t(dw.max.y) - dw.min.y + 1);
    part.bytes_per_pixel = bytes_per_pixel(ctx, p);
    part.chunk_bytes = chunk_pixels(ctx, p, part.width) * double(part.bytes_per_pixel);
    const double chunk_bytes = std::max(part.chunk_bytes, layout ? layout->chunk_bytes : 0.0);
    if (!layout || part.decoded_bytes() > layout->decoded_bytes()) layout = part;
    layout->chunk_bytes = chunk_bytes;
  }
  exr_finish(&ctx);
  return layout;
}

}  // namespace insitu
