// glTF 2.0 materials as insitu's principled materials (render/mesh.h, render/bsdf.h), for
// render/gltf_mesh.cpp. What Blender's glTF importer sets on the Principled BSDF is what insitu
// reads, so that both render one asset alike:
//   pbrMetallicRoughness.baseColorFactor × baseColorTexture (sRGB)   → base colour (alpha ignored)
//     (8-bit colour decoded after interpolation, as Cycles: render/texture.h)
//   metallicFactor × texture B, roughnessFactor × texture G (linear) → metallic, roughness
//   KHR_materials_transmission × texture R, KHR_materials_ior         → transmission, IOR (glass)
//   KHR_materials_volume (a thickness): attenuationColor, _Distance    → σ_a = (1 − colour)/distance
//   KHR_materials_specular: specularColorFactor (× specularFactor)   → specular, specular tint
//   KHR_materials_clearcoat, _sheen, _emissive_strength, normalTexture, alphaMode (read below)
// Textures through texCoord 0 or 1 and KHR_texture_transform (render/texture.h), repeating.
// What a material uses and insitu does not render (the clear coat's normal map, the specular
// extension's textures, other extensions, wrap modes other than REPEAT) is a warning naming the
// material.
#pragma once
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "core/error.h"
#include "render/mesh.h"

namespace insitu {

// Every material of the model, in its order, then glTF's default material (white, metallic 1,
// roughness 1) for primitives that name none (gltf_mesh.cpp drops it when none does). Throws InputError("file:
// $.materials[i]...", ...).
std::vector<Material> gltf_materials(const tinygltf::Model& model, const std::string& path, Warnings& warnings);

// The files a glTF reads besides itself (its buffers' and images' URIs that are not data URIs),
// found from the JSON alone. Nothing throws: load_gltf reports unreadable files.
std::vector<std::string> gltf_dependencies(const std::string& path);

}  // namespace insitu
