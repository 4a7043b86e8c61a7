// What `insitu render` takes from its command line, shared with `insitu merge` (which loads the
// scene again as its parts were rendered): the scene file with the overrides.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "scene/scene_file.h"

namespace insitu {

struct RenderArgs {
  std::string scene, output, layers, integrator, irradiance, tonemap;
  double key = 0;
  int spp = 0;
  long seed = -1;
  double noise_target = -1;  // --noise-target (0: off); −1: the scene's
  bool resume = false;
  bool denoise = false;       // --denoise: the composite denoised (output/denoise.h)
  std::string samples, part;  // --samples A:B and --part PATH: a part of a split render
};

// The scene file with the command line's overrides.
SceneSpec render_spec(const RenderArgs& a);

// The arguments the render's sums depend on (the scene, as an absolute path, and the overrides of
// spp, seed, integrator and irradiance mode), as a part file records them for `insitu merge`.
nlohmann::json sum_args_json(const RenderArgs& a);
// A part's record: those arguments ("args"), and the seconds it took to prepare and render.
struct PartRecord {
  RenderArgs args;
  std::string args_text;  // as recorded, to compare parts
  double prepare_seconds = 0, render_seconds = 0;
};
// `where` names the part in errors.
PartRecord part_record_from_json(const std::string& text, const std::string& where);

}  // namespace insitu
