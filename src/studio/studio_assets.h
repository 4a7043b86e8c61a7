// The studio's page (src/studio/page/: plain HTML, JavaScript and CSS, no build step), compiled
// into the binary by cmake/embed_files.cmake so that `insitu studio` needs no files at run time.
#pragma once
#include <cstddef>
#include <string>

namespace insitu {

struct StudioAsset {
  const char* name;  // file name, e.g. "studio.js"; nullptr ends the table
  const unsigned char* data;
  std::size_t size;
};

extern const StudioAsset kStudioAssets[];

// The asset of that file name, or nullptr.
inline const StudioAsset* studio_asset(const std::string& name) {
  for (const StudioAsset* a = kStudioAssets; a->name; ++a)
    if (name == a->name) return a;
  return nullptr;
}

}  // namespace insitu
