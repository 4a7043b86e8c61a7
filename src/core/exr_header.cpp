#include "core/exr_header.h"

#include <OpenEXR/openexr.h>

#include <fstream>

namespace insitu {

namespace {
void quiet(exr_const_context_t, exr_result_t, const char*) {}

bool has_exr_magic(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char magic[4] = {0, 0, 0, 0};
  in.read(reinterpret_cast<char*>(magic), 4);
  return in && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01;
}
}  // namespace

std::optional<std::pair<std::int64_t, std::int64_t>> exr_declared_size(const std::string& path) {
  if (!has_exr_magic(path)) return std::nullopt;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = quiet;
  exr_context_t ctx = nullptr;
  std::optional<std::pair<std::int64_t, std::int64_t>> size;
  int parts = 0;
  if (exr_start_read(&ctx, path.c_str(), &init) == EXR_ERR_SUCCESS && exr_get_count(ctx, &parts) == EXR_ERR_SUCCESS) {
    for (int p = 0; p < parts; ++p) {
      exr_attr_box2i_t dw;
      if (exr_get_data_window(ctx, p, &dw) != EXR_ERR_SUCCESS) continue;
      const std::int64_t w = std::int64_t(dw.max.x) - dw.min.x + 1, h = std::int64_t(dw.max.y) - dw.min.y + 1;
      if (!size || w * h > size->first * size->second) size = std::make_pair(w, h);
    }
  }
  exr_finish(&ctx);
  return size;
}

}  // namespace insitu
