#include "render/obj_materials.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "render/obj_statements.h"

namespace insitu {
namespace fs = std::filesystem;
using namespace obj_text;

namespace {

bool has(const std::set<std::string>& statements, const char* key) { return statements.count(key) > 0; }

// The statements that make a material principled (the PBR extension's).
bool principled_statements(const std::set<std::string>& statements) {
  for (const char* key : {"Pr", "Pm", "Ps", "Pc", "Pcr", "aniso", "anisor", "map_Pr", "map_Pm", "map_Ps", "norm"})
    if (has(statements, key)) return true;
  return false;
}

// One value's range, by keyword: reflectances and opacity in [0, 1], the PBR factors in [0, 1],
// the ambient and emitted colours and the exponent ≥ 0.
void check_range(const std::string& path, int line, const std::string& kw, const std::string& text) {
  static const std::set<std::string> kUnit = {"Kd", "Ks", "Tf", "Kt", "d", "Pr", "Pm", "Ps", "Pc", "Pcr", "aniso"};
  const double v = std::strtod(text.c_str(), nullptr);
  if (kUnit.count(kw) && (v < 0 || v > 1)) {
    const char* what = kw == "d"                    ? "an opacity"
                       : (kw == "Kd" || kw == "Ks") ? "a reflectance"
                       : (kw == "Tf" || kw == "Kt") ? "a transmittance"
                                                    : "a factor";
    fail(path, line, fmt::format("{} {} is outside [0, 1] ({})", kw, text, what));
  }
  if ((kw == "Ka" || kw == "Ke" || kw == "Ns") && v < 0) fail(path, line, fmt::format("{} {} is negative", kw, text));
}

// A colour statement's value. The MTL specification's "Kd r [g b]": one number is a grey, which
// tinyobjloader reads as (r, 0, 0) (and Blender's importer as r with its own defaults for g and
// b); scan_mtl marks such a statement "Kd 1".
Rgb colour_of(const tinyobj::real_t* c, const std::set<std::string>& statements, const std::string& kw) {
  if (has(statements, (kw + " 1").c_str())) return Rgb::Constant(float(c[0]));
  return Rgb(float(c[0]), float(c[1]), float(c[2]));
}

// A texture statement's options -o and -s as Blender 3.4's importer reads them, a Mapping node of
// that Location and Scale before the image: (u, v) → s·(u, v) + o, then the OBJ convention's
// (u′, 1 − v′) (render/texture.h).
Eigen::Matrix<float, 2, 3> image_from_uv(const tinyobj::texture_option_t& opt, const std::string& where) {
  const float su = float(opt.scale[0]), sv = float(opt.scale[1]);
  const float ou = float(opt.origin_offset[0]), ov = float(opt.origin_offset[1]);
  if (!std::isfinite(su) || !std::isfinite(sv) || !std::isfinite(ou) || !std::isfinite(ov))
    throw InputError(where, "the texture options -o and -s must be finite numbers");
  Eigen::Matrix<float, 2, 3> a;
  a << su, 0, ou, 0, -sv, 1 - ov;
  return a;
}

// A texture of the material, read beside the OBJ: colour (sRGB where the file is 8-bit) or data,
// with its alpha channel where `alpha` keeps it, placed by its -o and -s.
Texture read_texture(const std::string& name, const tinyobj::texture_option_t& opt, bool colour,
                     const fs::path& base_dir, const std::string& where, const char* statement,
                     AlphaChannel alpha = AlphaChannel::kDrop) {
  Texture t;
  const std::string file = beside_obj(base_dir, name);
  try {
    ImageFile image = read_texture_file(file, alpha);
    if (alpha == AlphaChannel::kKeep) t.alpha = alpha_texels_of(image);
    colour ? set_colour_image(t, std::move(image)) : set_data_image(t, std::move(image));
    t.path = file;
    t.image_from_uv = image_from_uv(opt, file);
  } catch (const InputError& e) {
    throw e.with_context(where + ": " + statement);
  }
  return t;
}

// A normal map points out of the surface: over its texels, the mean of 2b − 1 exceeds ½, and its
// channels are not all equal (a grey image is a height map).
bool is_normal_map(const Texture& t) {
  const Texels& img = *t.image;
  double z = 0;
  bool grey = true;
  const int step = std::max(1, std::max(img.width(), img.height()) / 64);
  std::size_t n = 0;
  for (int j = 0; j < img.height(); j += step)
    for (int i = 0; i < img.width(); i += step, ++n) {
      const Rgb c = img.rgb(i, j);
      z += 2.0 * c[2] - 1.0;
      grey = grey && c[0] == c[1] && c[1] == c[2];
    }
  return !grey && z > 0.5 * double(n);
}

// `norm`, or map_Bump where its image is a normal map; -bm is the Normal Map node's strength.
void read_normal_map(const tinyobj::material_t& m, Material& out, const fs::path& base_dir, const std::string& where,
                     Warnings& warnings) {
  if (!m.normal_texname.empty()) {
    out.map_normal = read_texture(m.normal_texname, m.normal_texopt, false, base_dir, where, "norm");
    out.normal_strength = float(m.normal_texopt.bump_multiplier);
  } else if (!m.bump_texname.empty()) {
    Texture bump = read_texture(m.bump_texname, m.bump_texopt, false, base_dir, where, "map_Bump");
    if (!is_normal_map(bump)) {
      warnings.add(where, "map_Bump is a height map (grey, or not pointing out of the surface): not rendered");
      return;
    }
    out.map_normal = std::move(bump);
    out.normal_strength = float(m.bump_texopt.bump_multiplier);
  }
  if (!std::isfinite(out.normal_strength) || out.normal_strength < 0)
    throw InputError(where, "the normal map's -bm must be a finite number ≥ 0");
}

// Ke × map_Ke (sRGB), both models; Ke is 1 where only the map is given.
void read_emission(const tinyobj::material_t& m, const std::set<std::string>& statements, Material& out,
                   const fs::path& base_dir, const std::string& where) {
  out.emission = colour_of(m.emission, statements, "Ke");
  if (m.emissive_texname.empty()) return;
  out.map_emission = read_texture(m.emissive_texname, m.emissive_texopt, true, base_dir, where, "map_Ke");
  if (!has(statements, "Ke")) out.emission = Rgb::Ones();
}

// `d` and `map_d`: a stochastic opacity (Material::opacity) wherever either makes the surface
// less than opaque, as Cycles renders the Principled BSDF's Alpha that Blender's importer links
// them to. map_d keeps its alpha channel (the importer links the image's Alpha); without one its
// grey is the opacity. `Tr`, which exporters write as 1 − d or as d, is ignored, as Blender does
// (tinyobjloader reads it as 1 − d where `d` is absent). scan_mtl has checked d within [0, 1].
void read_opacity(const tinyobj::material_t& m, const std::set<std::string>& statements, Material& out,
                  const fs::path& base_dir, const std::string& where, Warnings& warnings) {
  out.alpha = has(statements, "d") ? float(m.dissolve) : 1.0f;
  if (out.alpha == 0) warnings.add(where, "d 0: the surface is fully transparent, and not seen");
  if (!m.alpha_texname.empty())
    out.map_opacity =
        read_texture(m.alpha_texname, m.alpha_texopt, false, base_dir, where, "map_d", AlphaChannel::kKeep);
  if (out.alpha < 1 || out.map_opacity) out.alpha_mode = Material::AlphaMode::kBlend;
}

// Tf (or Kt) and Ni as Blender 3.4's importer and exporter read and write them in the principled
// model: the Principled BSDF's Transmission, the mean of Tf, and its IOR; without Ni a new
// Principled BSDF's 1.45. scan_mtl has checked Tf within [0, 1]; the index must be where glTF's
// KHR_materials_ior puts it, [1, 10], wherever a transmission makes it matter.
void read_glass(const tinyobj::material_t& m, const std::set<std::string>& statements, Material& out,
                const std::string& where) {
  const char* tf = has(statements, "Tf") ? "Tf" : "Kt";
  if (!has(statements, tf)) return;
  out.transmission = colour_of(m.transmittance, statements, tf).mean();
  out.ior = has(statements, "Ni") ? float(m.ior) : 1.45f;
  if (out.transmission > 0 && !(out.ior >= 1 && out.ior <= 10))
    throw InputError(where,
                     fmt::format("Ni {} with {}: a transmitting material's index must be within [1, 10]", m.ior, tf));
}

// The principled parameters (the header's table).
void read_principled(const tinyobj::material_t& m, const std::set<std::string>& statements, Material& out,
                     const fs::path& base_dir, const std::string& where, Warnings& warnings) {
  out.principled = true;
  if (has(statements, "Pr"))
    out.roughness = float(m.roughness);
  else if (!m.roughness_texname.empty() || !has(statements, "Ns"))
    out.roughness = 1.0f;
  else
    out.roughness = 1.0f - std::sqrt(std::clamp(float(m.shininess), 0.0f, 1000.0f) / 1000.0f);
  out.metallic = has(statements, "Pm") ? float(m.metallic) : m.metallic_texname.empty() ? 0.0f : 1.0f;
  out.specular = has(statements, "Ks") ? out.ks.mean() : 0.5f;
  out.clearcoat = float(m.clearcoat_thickness);
  out.clearcoat_roughness = float(m.clearcoat_roughness);
  read_glass(m, statements, out, where);
  if (!m.roughness_texname.empty())
    out.map_roughness = read_texture(m.roughness_texname, m.roughness_texopt, false, base_dir, where, "map_Pr");
  if (!m.metallic_texname.empty())
    out.map_metallic = read_texture(m.metallic_texname, m.metallic_texopt, false, base_dir, where, "map_Pm");
  std::string unread;
  for (const char* key : {"Ps", "map_Ps", "aniso", "anisor"})
    if (has(statements, key)) unread += fmt::format("{}{}", unread.empty() ? "" : ", ", key);
  if (!unread.empty())
    warnings.add(where, fmt::format("not rendered: {} (insitu's principled material has no sheen weight or "
                                    "anisotropy; docs/materials.md)",
                                    unread));
}

}  // namespace

void scan_mtl(const std::string& path, MtlStatements& out) {
  std::ifstream in(path);
  if (!in) return;  // a missing MTL is tinyobjloader's warning
  std::set<std::string>* current = nullptr;
  static const std::set<std::string> kColours = {"Kd", "Ks", "Ka", "Ke", "Tf", "Kt"};
  static const std::set<std::string> kScalars = {"Ns", "Ni", "d", "Pr", "Pm", "Ps", "Pc", "Pcr", "aniso", "anisor"};
  for_each_statement(in, [&](int lineno, const std::vector<std::string>& tok) {
    const std::string& kw = tok[0];
    if (kw == "newmtl") {
      current = &out[tok.size() > 1 ? tok[1] : std::string()];
      return;
    }
    if (current) current->insert(kw);
    const bool colour = kColours.count(kw) > 0;
    if (!colour && !kScalars.count(kw)) return;
    if (colour && tok.size() > 1 && tok[1] == "spectral") return;
    check_numbers(path, lineno, tok, colour ? (tok.size() == 2 ? 1 : 3) : 1, colour ? 3 : 1, kw.c_str());
    if (colour && current) {  // a grey, one number (colour_of); the last statement counts
      if (tok.size() == 2)
        current->insert(kw + " 1");
      else
        current->erase(kw + " 1");
    }
    for (std::size_t k = 1; k < tok.size() && k <= (colour ? 3u : 1u); ++k) check_range(path, lineno, kw, tok[k]);
  });
}

std::string beside_obj(const fs::path& base_dir, const std::string& name) { return (base_dir / name).string(); }

std::vector<std::string> material_files(const tinyobj::material_t& m, const fs::path& base_dir) {
  std::vector<std::string> files;
  for (const std::string* name : {&m.diffuse_texname, &m.emissive_texname, &m.normal_texname, &m.bump_texname,
                                  &m.roughness_texname, &m.metallic_texname, &m.alpha_texname})
    if (!name->empty()) files.push_back(beside_obj(base_dir, *name));
  return files;
}

Material convert_material(const tinyobj::material_t& m, const std::set<std::string>& statements,
                          const fs::path& base_dir, const std::string& obj_path, Warnings& warnings) {
  Material out;
  out.name = m.name;
  out.kd = colour_of(m.diffuse, statements, "Kd");
  out.ks = colour_of(m.specular, statements, "Ks");
  out.ns = float(m.shininess);
  const std::string where = fmt::format("{}: material '{}'", obj_path, m.name);
  if (!out.kd.allFinite() || (out.kd < 0).any()) throw InputError(where, "Kd must be finite and non-negative");
  if (!m.diffuse_texname.empty())
    out.map_kd = read_texture(m.diffuse_texname, m.diffuse_texopt, true, base_dir, where, "map_Kd");
  read_opacity(m, statements, out, base_dir, where, warnings);
  read_emission(m, statements, out, base_dir, where);
  read_normal_map(m, out, base_dir, where, warnings);
  if (principled_statements(statements)) read_principled(m, statements, out, base_dir, where, warnings);
  return out;
}

}  // namespace insitu
