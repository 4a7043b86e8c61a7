// The demo's catalogue asset (scenes/demo/chair.glb): an armchair and its side table as one glTF 2.0
// binary, written with tinygltf, in the four material classes a catalogue sells:
//
// - lacquered walnut (the chair's frame): a textured base under a glossy clear coat
//   (KHR_materials_clearcoat), its grain in relief by a tangent-space normal map;
// - upholstery (the cushions): a rough base under a pale sheen (KHR_materials_sheen);
// - brushed steel (the legs): metallic;
// - tinted glass (the table's top): KHR_materials_transmission with a KHR_materials_volume
//   absorption, so that the photo's floor is seen through it and its shadow is coloured.
//
// Metres, +Y up, the chair facing +Z, its origin on the floor under the seat's centre.
#pragma once
#include <string>

namespace insitu {

// Writes the .glb; throws std::runtime_error when it cannot.
void write_demo_chair(const std::string& glb_path);

}  // namespace insitu
