// The room's light as a radiance cube, from six shots or from an HDR image (equirectangular
// 2:1, or a vertical strip of the six faces 1:6), in the photo's radiance unit times `scale`.
#pragma once
#include <array>

#include "cubemap.h"
#include "error.h"
#include "scene.h"

namespace insitu {

struct EnvironmentInfo {
  std::size_t clamped_values = 0;  // negative or non-finite input values set to 0
  std::array<double, 6> coverage = {1, 1, 1, 1, 1, 1};  // per face, from six shots
  int face_size = 0;
};

// An environment named on the command line: a scene file (its environment) or an HDR image.
EnvironmentSpec environment_from_argument(const std::string& path);

CubeMap load_environment(const EnvironmentSpec& spec, Warnings& warnings, EnvironmentInfo* info = nullptr);

}  // namespace insitu
