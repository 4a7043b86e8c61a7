// Triangle meshes from glTF 2.0 (.gltf with its .bin and images, .glb, data URIs; tinygltf parses,
// OpenImageIO decodes the images).
//
// Every mesh of the default scene's node tree, placed by its node's world transform (the
// product of the node matrices, or T·R·S, from the root; normals by the inverse transpose), is
// one Mesh: glTF's metres and +Y up are insitu's. Primitives of mode TRIANGLES (4, the default);
// other modes are skipped with a warning. POSITION, NORMAL, TEXCOORD_0 and TEXCOORD_1 (float, or
// a signed or unsigned byte or short, normalized or not: KHR_mesh_quantization) and the indices
// (unsigned byte, short or int) are read with their bounds checked, sparse accessors included
// (glTF 2.0 §3.6.2.3: zeros without a buffer view); UVs are turned to OBJ's
// convention (v = 1 − v, render/texture.h). Draco and meshopt compression: render/gltf_decompress.h.
// Materials: render/gltf_materials.h.
//
// Refused, as InputError naming the file and the JSON path or the accessor: a file tinygltf
// cannot parse (a missing buffer, bad JSON), an extension in extensionsRequired that insitu does
// not support, an accessor out of its buffer, an index out of range, a non-finite position, a
// node cycle, a file without triangles. Degenerate triangles are dropped and counted.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "render/mesh.h"

namespace insitu {

Mesh load_gltf(const std::string& path, Warnings& warnings);

// A Draco- or meshopt-compressed file decompressed into a self-contained .glb (plain_glb in
// render/gltf_decompress.h); nothing for a file without compression.
std::optional<std::string> gltf_plain_copy(const std::string& path);

// A .gltf or .glb by its extension.
bool is_gltf_path(const std::string& path);

// load_gltf or load_obj by the file's extension; and the files each reads besides itself.
Mesh load_mesh(const std::string& path, Warnings& warnings);
std::vector<std::string> mesh_dependencies(const std::string& path);

}  // namespace insitu
