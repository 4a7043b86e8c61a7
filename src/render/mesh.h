// Triangle meshes from OBJ + MTL (tinyobjloader does the parsing; render/obj_materials.h the MTL).
//
// Before tinyobjloader reads a file, a validating pass over its text checks what tinyobjloader
// lets through silently, so that every error names its line: non-finite or missing coordinates
// (`v`, `vn`, `vt`), face indices that are 0 or out of range, faces with fewer than three
// vertices. Polygons are split into fans (0, i, i+1); degenerate triangles (zero area relative
// to their edge lengths) and exact copies of a triangle already read (the same three corners, in
// any order) are dropped and counted as a warning.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image.h"
#include "core/math.h"
#include "render/texture.h"

namespace insitu {

// Cycles's approximate luminance, 0.3 R + 0.6 G + 0.1 B, by which its Principled BSDF tints the
// specular layer (kernel/svm/closure.h) and Blender's glTF importer converts
// KHR_materials_specular; not Rec.709's luminance (core/math.h), which Cycles's sheen uses.
inline float cycles_tint_luminance(const Rgb& c) { return 0.3f * c[0] + 0.6f * c[1] + 0.1f * c[2]; }

// A surface's material. OBJ's MTL gives the first block (the `obj` model of render/bsdf.h), or
// with the PBR extension's statements the principled model (render/obj_materials.h); glTF always
// gives the principled model (Cycles 3.4's Principled BSDF, render/bsdf.h),
// whose parameters are Cycles's own: base colour, metallic, roughness r (α = r²), specular
// (F0 = 0.08 · specular for a dielectric; 0.5 is glTF's ior 1.5).
struct Material {
  std::string name = "default";
  Rgb kd = Rgb(0.8f, 0.8f, 0.8f);  // diffuse reflectance, the base colour (linear)
  Rgb ks = Rgb::Zero();            // specular reflectance, kept for the glossy lobe
  float ns = 0.0f;                 // Phong exponent
  Texture map_kd;                  // multiplies kd

  bool principled = false;  // the principled model, with the parameters below
  float metallic = 0.0f, roughness = 0.5f, specular = 0.5f;
  Texture map_metallic_roughness;       // glTF's: G multiplies roughness, B metallic
  Texture map_roughness, map_metallic;  // MTL's map_Pr and map_Pm: their grey (luminance) multiplies
  float clearcoat = 0.0f, clearcoat_roughness = 0.0f;
  Texture map_clearcoat, map_clearcoat_roughness;  // glTF's: R multiplies clearcoat, G its roughness
  Rgb sheen = Rgb::Zero();                         // KHR_materials_sheen's colour (a Velvet BSDF)
  float sheen_roughness = 0.0f;
  Texture map_sheen, map_sheen_roughness;  // sRGB colour; the roughness in the alpha channel

  // Glass (KHR_materials_transmission, _ior, _volume as Blender 3.4 imports them): the Principled
  // BSDF's transmission (× R of its texture) and IOR; inside a closed mesh of non-zero thickness,
  // Cycles's Volume Absorption of colour c and density 1/d, σ_a = (1 − c)/d per metre.
  float transmission = 0.0f, ior = 1.5f;
  Texture map_transmission;
  Rgb absorption = Rgb::Zero();  // σ_a, 1/m

  // A tangent-space normal map (linear RGB, 2c − 1 per channel; Mesh::tangents), with Cycles's
  // Normal Map strength: glTF's normalTexture.scale, as Blender imports it.
  Texture map_normal;
  float normal_strength = 1.0f;
  // The clear coat's own (KHR_materials_clearcoat's clearcoatNormalTexture, Blender's Clearcoat
  // Normal); without it the coat keeps the smooth normal, however map_normal bends the rest.
  Texture map_clearcoat_normal;
  float clearcoat_normal_strength = 1.0f;
  // The map whose UV set Mesh::tangents follow: the normal map's, else the coat's.
  const Texture& tangent_map() const { return map_normal ? map_normal : map_clearcoat_normal; }

  // KHR_materials_specular as Blender 3.4's importer reads it: the Principled BSDF's Specular from
  // its colour's luminance, the transmission and the index at each point (specular_at), and its
  // Specular Tint from its colour against the base colour (specular_tint). Without the extension,
  // `specular` above and no tint.
  bool has_specular_colour = false;
  Rgb specular_colour = Rgb::Ones();  // specularColorFactor
  float specular_factor = 1.0f;       // specularFactor
  Texture map_specular_colour;        // specularColorTexture: sRGB, multiplies specular_colour
  Texture map_specular;               // specularTexture: its alpha multiplies specular_factor

  Rgb emission = Rgb::Zero();  // emitted radiance, in the environment's units (Cycles's strength 1)
  Texture map_emission;        // multiplies emission

  // glTF's alphaMode: opaque; a mask, opaque where alpha ≥ alpha_cutoff and absent elsewhere; or
  // a blend, present with probability alpha (stochastic opacity).
  enum class AlphaMode { kOpaque, kMask, kBlend };
  AlphaMode alpha_mode = AlphaMode::kOpaque;
  float alpha = 1.0f, alpha_cutoff = 0.5f;  // alpha: the base colour's, times map_kd's alpha channel
  // MTL's opacity, as Blender 3.4's OBJ importer links `map_d` to the Principled BSDF's Alpha:
  // alpha (`d`) times its alpha channel, or its grey (luminance, as data) where it has none.
  // (An MTL's map_Kd keeps no alpha channel: the importer leaves it out.)
  Texture map_opacity;

  Rgb base_colour(const UvSets& uv) const { return kd * map_kd.sample(uv); }
  Rgb emitted(const UvSets& uv) const { return emission * map_emission.sample(uv); }
  // The probability that a ray meets the surface here: 1 or 0 for opaque and mask, alpha for blend.
  float opacity(const UvSets& uv) const;
  // The Specular Tint in [0, 1] of a specular colour over a base colour (0 without
  // KHR_materials_specular); the one-argument form for specular_colour.
  float specular_tint(const Rgb& base, const Rgb& colour) const;
  float specular_tint(const Rgb& base) const { return specular_tint(base, specular_colour); }
  Rgb specular_colour_at(const UvSets& uv) const { return specular_colour * map_specular_colour.sample(uv); }
  // The principled Specular at a point of transmission t (render/mesh.cpp).
  float specular_at(const UvSets& uv, float t) const;
  bool cutout() const { return alpha_mode != AlphaMode::kOpaque; }
};

struct Triangle {
  std::array<std::uint32_t, 3> v;  // into positions
  std::array<std::int32_t, 3> n;   // into normals, -1: use the geometric normal
  std::array<std::int32_t, 3> t;   // into uvs, -1: none
  std::int32_t material;           // into materials
};

struct Mesh {
  std::string source;              // the OBJ path, for messages
  std::vector<std::string> files;  // every file it was read from: the OBJ, its MTL files, textures
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;
  std::vector<Vec2f> uvs;
  std::vector<Vec2f> uvs1;  // a second UV set, indexed as uvs (glTF's TEXCOORD_1), or empty
  std::vector<Triangle> triangles;
  // Per triangle corner (3 per triangle): the tangent of the normal map's UV set (xyz) and the
  // bitangent's sign (w; render/tangents.h). Empty where no material has a normal map.
  std::vector<Vec4f> tangents;
  std::vector<Material> materials;  // never empty: a default material is added when needed
};

// Throws InputError("file:line", ...) on bad input; adds counted warnings.
Mesh load_obj(const std::string& path, Warnings& warnings);

// The files an OBJ reads besides itself, as load_obj resolves them: its MTL files (`mtllib`, beside
// the OBJ) and their diffuse textures (`map_Kd`), found by reading only those statements (a batch
// checks its outputs against them before it loads anything). Unreadable files list nothing more;
// nothing throws: load_obj reports them.
std::vector<std::string> obj_dependencies(const std::string& obj_path);

// A triangle whose edges are parallel or zero: |e1 × e2| ≤ 1e-12 (|e1|² + |e2|²), in double.
bool degenerate_triangle(const Mesh& mesh, const Triangle& tri);

// Applies an affine transform (positions by M, normals by its inverse transpose, tangents by M and
// their sign by det M's).
void transform_mesh(Mesh& mesh, const Mat4d& M_world_from_object);

struct Bounds {
  Vec3f lo = Vec3f::Constant(std::numeric_limits<float>::infinity());
  Vec3f hi = Vec3f::Constant(-std::numeric_limits<float>::infinity());
  void extend(const Vec3f& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
};
Bounds mesh_bounds(const Mesh& mesh);

}  // namespace insitu
