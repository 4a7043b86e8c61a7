// The meshes of the Blender export (interop/blender_export.h): their triangles appended to the
// binary file in the layout the script's load_mesh reads, and the Python lines that create their
// materials and objects.
#pragma once
#include <optional>
#include <string>

#include "interop/blender_camera.h"
#include "render/mesh.h"

namespace insitu {

// A Python literal: a string (JSON's escapes are Python's) or an RGB tuple.
std::string py_string(const std::string& s);
std::string py_rgb(const Rgb& c);

// Appends the mesh to `bytes` and returns the lines that load it as object `name` from the file
// in the Python variable MESHES. An object gets a material per MTL material; a catcher
// (`catcher_albedo` set) one Lambertian material of that albedo and Cycles' shadow catcher flag.
std::string blender_mesh(const Mesh& mesh, const std::string& name, const std::optional<Rgb>& catcher_albedo,
                         std::string& bytes);

// The line that imports a glTF asset with Blender's own importer (its materials as Blender reads
// them: the Principled BSDF) as object `name`, placed by insitu's M_world_from_object. The
// importer turns glTF's +Y up to Blender's +Z up by B (blender_camera.h), so the imported asset
// is B·p and the object's matrix is B·M·B⁻¹. `py_path`: a Python expression for the file.
std::string blender_gltf_object(const std::string& py_path, const std::string& name, const Mat4d& M_world_from_object);

}  // namespace insitu
