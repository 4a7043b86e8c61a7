// MTL materials. tinyobjloader parses them; a validating pass first checks the values it reads
// silently (NaN, out-of-range factors) and notes which statements each material has, since
// tinyobjloader gives an absent statement its default.
//
// A classic material (Kd × map_Kd, Ks, Ns) is the `obj` model of render/bsdf.h. A material with
// any statement of the PBR extension (Pr, Pm, Ps, Pc, Pcr, aniso, anisor, map_Pr, map_Pm, map_Ps,
// norm; exocortex.com's "Extending Wavefront MTL to support PBR") is the principled model, with
// the values Blender 3.4's OBJ importer (obj_import_mtl.cc) gives its Principled BSDF:
//   base colour  Kd × map_Kd
//   metallic     Pm × map_Pm
//   roughness    Pr × map_Pr; without Pr, 1 − √(Ns/1000) (Ns clamped to [0, 1000]), or 1 without Ns
//   specular     the mean of Ks, or Cycles's default 0.5 without Ks
//   clear coat   Pc, its roughness Pcr
//   glass        transmission the mean of Tf (or Kt), IOR Ni (1.45 without it), as Blender's
//                exporter writes them
// A map multiplies its statement's value, which is 1 where only the map is given. The departures
// from Blender's importer (docs/materials.md): Blender links a map in place of the value and
// reads 8-bit roughness, metallic and normal maps as sRGB colour (insitu: as stored data); without
// Ks it gives specular 0; under illum 3–9 it takes metallic from Ka; and it reads Tf as a
// transmission in the classic model too.
//
// A colour given as one number is a grey, as the MTL specification says (tinyobjloader reads
// (r, 0, 0)). Both models read Ke × map_Ke as emission and a tangent-space normal map from `norm`, or from
// map_Bump/bump where that image is a normal map (as Blender's exporter writes them; a grey height
// map is named in a warning). Ps, aniso and anisor are named as not rendered.
#pragma once
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <tiny_obj_loader.h>

#include "render/mesh.h"

namespace insitu {

// Per material name, the statements its MTL gives (their keywords).
using MtlStatements = std::map<std::string, std::set<std::string>>;

// Checks an MTL file's values line by line, throwing InputError("file:line", ...), and adds its
// materials' statements to `out`. A missing file adds nothing (tinyobjloader warns of it).
void scan_mtl(const std::string& path, MtlStatements& out);

// Where an OBJ's MTL files and their textures are read: beside the OBJ, as tinyobjloader's
// mtl_search_path makes it. load_obj, convert_material and obj_dependencies all ask here, so the
// files a batch checks before loading are the files loading reads.
std::string beside_obj(const std::filesystem::path& base_dir, const std::string& name);

// The texture files a material reads.
std::vector<std::string> material_files(const tinyobj::material_t& m, const std::filesystem::path& base_dir);

// insitu's material from tinyobjloader's and the statements the MTL gave it.
Material convert_material(const tinyobj::material_t& m, const std::set<std::string>& statements,
                          const std::filesystem::path& base_dir, const std::string& obj_path, Warnings& warnings);

}  // namespace insitu
