#include "environment.h"

#include <filesystem>
#include <fmt/format.h>

#include "equirect.h"
#include "sixshot.h"

namespace insitu {

EnvironmentSpec environment_from_argument(const std::string& path) {
  std::string ext = path.size() >= 5 ? path.substr(path.size() - 5) : "";
  for (auto& c : ext) c = char(std::tolower(c));
  if (ext == ".json") return parse_scene_file(path).environment;
  if (!std::filesystem::exists(path)) throw InputError(path, "file not found");
  EnvironmentSpec spec;
  spec.image = path;
  return spec;
}

CubeMap load_environment(const EnvironmentSpec& spec, Warnings& warnings, EnvironmentInfo* info) {
  EnvironmentInfo local;
  CubeMap cube;
  if (!spec.from_shots()) {
    Image img;
    try {
      img = linearize(read_image_file(spec.image), &local.clamped_values);
    } catch (const InputError& e) {
      throw e.with_context(spec.where);
    }
    if (img.width == 2 * img.height) {
      cube = cube_from_equirect(img, spec.face_size > 0 ? spec.face_size : std::max(1, img.width / 4));
    } else if (img.height == 6 * img.width) {
      cube = cube_from_strip(img);
      if (spec.face_size > 0 && spec.face_size != cube.size())
        throw InputError(spec.where, fmt::format("{}: a cube strip has face size {}, face_size asks for {}",
                                                 spec.image, cube.size(), spec.face_size));
    } else {
      throw InputError(spec.where, fmt::format("{}: {}x{} is neither equirectangular (2:1) nor a cube strip (1:6)",
                                               spec.image, img.width, img.height));
    }
    if (local.clamped_values > 0)
      warnings.add(spec.image, fmt::format("{} negative or non-finite values clamped to 0", local.clamped_values));
  } else {
    ShotSet set;
    set.faced_face = spec.faced_face;
    set.set_hfov(spec.hfov_deg);
    for (int f = 0; f < 6; ++f) {
      std::size_t clamped = 0;
      try {
        set.shots[f] = linearize(read_image_file(spec.shots[f]), &clamped);
      } catch (const InputError& e) {
        throw e.with_context(spec.shot_where[f]);
      }
      set.names[f] = spec.shots[f];
      local.clamped_values += clamped;
      if (clamped > 0) warnings.add(spec.shots[f], fmt::format("{} negative or non-finite values clamped to 0", clamped));
    }
    const int n = spec.face_size > 0 ? spec.face_size : natural_face_size(set);
    AssemblyInfo assembly;
    try {
      cube = assemble_cube(set, n, &assembly);
    } catch (const InputError& e) {
      throw e.with_context(spec.where);
    }
    local.coverage = assembly.coverage;
    for (int f = 0; f < 6; ++f)
      if (assembly.coverage[std::size_t(f)] < 1.0)
        warnings.add(spec.shots[std::size_t(f)], fmt::format("covers {:.1f}% of face {}; the rest is filled from its neighbours",
                                                             100 * assembly.coverage[std::size_t(f)], face_name(f)));
  }
  if (spec.scale != 1.0) {
    CubeMap scaled(cube.size());
    for (int f = 0; f < 6; ++f)
      for (int j = -1; j <= cube.size(); ++j)
        for (int i = -1; i <= cube.size(); ++i) scaled.set_texel(f, i, j, cube.texel(f, i, j) * float(spec.scale));
    cube = std::move(scaled);
  }
  local.face_size = cube.size();
  if (info) *info = local;
  return cube;
}

}  // namespace insitu
