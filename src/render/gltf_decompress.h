// Compressed glTF geometry, decoded into plain buffers before the mesh is read (gltf_mesh.cpp):
//
// - KHR_draco_mesh_compression: a primitive's attributes and indices in one Draco bitstream,
//   decoded by Debian's libdraco. Each attribute named in the extension becomes a float accessor
//   (Draco dequantizes), the faces an unsigned int index accessor.
// - EXT_meshopt_compression: a buffer view's bytes in meshoptimizer's vertex or index codec, with
//   its OCTAHEDRAL, QUATERNION or EXPONENTIAL filter, decoded by Debian's libmeshoptimizer into a
//   buffer of its own.
//
// tinygltf has a Draco path of its own (TINYGLTF_ENABLE_DRACO); insitu does not use it: it indexes
// the file's buffer views and attributes unchecked and ignores a failed decode.
//
// Bounds: a meshopt view may not decode to more than 64 bytes per encoded byte (the vertex codec
// spends at least a 2-bit header per 16 bytes; the index codecs a byte per triangle or index), nor
// to more than 1 GiB. Every refusal is an InputError naming the file and the JSON path.
#pragma once
#include <string>
#include <tiny_gltf.h>

namespace insitu {

// The file's bytes as tinygltf 2.7 parses them: unchanged, or with each meshopt fallback buffer
// that lacks a uri given a 4-byte data URI, and each Draco primitive's index accessor that lacks a
// buffer view given the Draco stream's (tinygltf refuses both; decoding replaces both).
// `binary`: a .glb container, rebuilt around the changed JSON chunk.
std::string gltf_prepared_for_tinygltf(std::string bytes, bool binary);

// Decodes every compressed buffer view and primitive of `model` in place.
void decompress_gltf(tinygltf::Model& model, const std::string& path);

// Whether the file uses KHR_draco_mesh_compression or EXT_meshopt_compression.
bool gltf_is_compressed(const tinygltf::Model& model);

// A decompressed `model` as a self-contained .glb, for importers without the decoders (Blender
// 3.4's has neither: interop/blender_export.h): its buffers merged into the binary chunk, its
// images (PNG or JPEG) moved into it, the two extensions dropped. Throws InputError naming
// `path` for an image it cannot embed.
std::string plain_glb(tinygltf::Model model, const std::string& path);

}  // namespace insitu
