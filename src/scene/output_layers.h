// A render's results by name: the layers of the EXR that `insitu render` writes, and the image its
// PNG or JPEG holds. The one list behind the EXR file, the C API's insitu_result_layer and the
// Python module's numpy arrays, so that all three hold the same floats.
#pragma once
#include <string>
#include <vector>

#include "scene/pipeline.h"

namespace insitu {

struct OutputLayer {
  std::string name;                   // "composite", "objects", ..., "display"
  std::vector<std::string> channels;  // "R", "G", "B" (or "A", "X", "Y", "Z")
  Image image;                        // channels.size() channels
  bool in_exr = true;                 // false: "display" (what the PNG/JPEG holds)
  // The channel's name in the EXR: "R" for the composite, "objects.R" for the others.
  std::string exr_channel(std::size_t c) const { return name == "composite" ? channels[c] : name + "." + channels[c]; }
};

// Every layer is finite: ±inf (a variance that overflowed float) becomes the largest float of its
// sign, NaN 0. "display" is the composite tone-mapped for `output`'s format (scene.spec.output's
// by default), in [0, 1] before the 8-bit rounding.
// Every file the loaded scene read: scene_input_files and the meshes' MTL files and textures.
std::vector<NamedPath> loaded_scene_inputs(const LoadedScene& scene);
// Every file its meshes (objects and local scene) were read from: OBJ, MTL files, textures.
std::vector<NamedPath> loaded_mesh_files(const LoadedScene& scene);

std::vector<OutputLayer> output_layers(const LoadedScene& scene, const RenderResult& result,
                                       const OutputSpec* output = nullptr);

}  // namespace insitu
