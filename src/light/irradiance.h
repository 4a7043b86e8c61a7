// Diffuse irradiance from a radiance cube, three ways (docs/irradiance.md). All give
//   E(n) = ∫ L(ω) max(0, n·ω) dω
// in the same units: a white Lambertian surface with normal n has exitant radiance E(n)/π.
//
//   gaussian  the legacy method: π × (each face Gaussian-blurred on its own, gaussian_irradiance.h)
//             looked up along n; fast, and wrong wherever the light is not nearly constant.
//   sh9       Ramamoorthi & Hanrahan 2001: L projected on the 9 spherical harmonics of order ≤ 2
//             with each texel weighted by its exact solid angle, E(n) = Σ Â_l L_lm Y_lm(n),
//             Â_0 = π, Â_1 = 2π/3, Â_2 = π/4.
//   exact     the integral above over every texel of the cube, the cube taken as constant per
//             texel, evaluated at the texel centres of a small irradiance cube (32² per face by
//             default) and looked up bilinearly.
//
// irradiance_reference() is the brute-force integral at an arbitrary normal, every texel clipped
// to the hemisphere and integrated by Lambert's formula; the others are measured against it.
#pragma once
#include <array>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/name_table.h"
#include "light/cubemap.h"

namespace insitu {

// `volume` is the one mode that depends on position as well: SH9 probes in the room box
// (light/irradiance_volume.h), which only the irradiance integrator builds; make_irradiance and
// the cube-based reports take the three directional modes.
enum class IrradianceMode { kGaussian, kSh9, kExact, kVolume };
inline constexpr Named<IrradianceMode> kIrradianceModes[] = {{IrradianceMode::kGaussian, "gaussian"},
                                                             {IrradianceMode::kSh9, "sh9"},
                                                             {IrradianceMode::kExact, "exact"},
                                                             {IrradianceMode::kVolume, "volume"}};
inline bool is_directional(IrradianceMode mode) { return mode != IrradianceMode::kVolume; }
// One line on what the mode computes, for `insitu modes` and docs/cli.md (a mode without one is a
// -Wswitch warning).
inline const char* irradiance_mode_summary(IrradianceMode mode) {
  switch (mode) {
    case IrradianceMode::kGaussian:
      return "the legacy method: the cube blurred face by face with a "
             "Gaussian as wide as the face, looked up along the normal";
    case IrradianceMode::kSh9:
      return "the cube projected on nine spherical harmonics (Ramamoorthi & Hanrahan 2001)";
    case IrradianceMode::kExact:
      return "the integral over every texel of the cube, "
             "tabulated on a 32² cube and looked up bilinearly";
    case IrradianceMode::kVolume:
      return "by position too: SH9 probes of the room box and its "
             "openings, blended trilinearly; needs environment.room_box";
  }
  return "";
}
// The modes that depend on the normal alone, in the table's order: what make_irradiance, the
// irradiance report and `insitu cubemap` take.
inline std::vector<IrradianceMode> directional_irradiance_modes() {
  std::vector<IrradianceMode> modes;
  for (const auto& row : kIrradianceModes)
    if (is_directional(row.value)) modes.push_back(row.value);
  return modes;
}
inline const char* irradiance_mode_name(IrradianceMode mode) { return name_of(kIrradianceModes, mode); }
inline std::optional<IrradianceMode> parse_irradiance_mode(const std::string& name) {
  return parse_name(kIrradianceModes, name);
}
inline std::string irradiance_mode_list() { return quoted_choices(names_of(kIrradianceModes)); }

class IrradianceField {
 public:
  virtual ~IrradianceField() = default;
  virtual Rgb irradiance(const Vec3f& normal_unit) const = 0;
};

// A directional mode's field (kVolume is a logic error here). `stop`: core/stop.h.
std::unique_ptr<IrradianceField> make_irradiance(IrradianceMode mode, const CubeMap& radiance, int exact_size = 32,
                                                 const std::atomic<bool>* stop = nullptr);

// The field as a cube of `n`² texels a face: E(texel direction) · scale (scale 1/π: the radiance of
// a white Lambertian surface facing that way, for previews). Borders updated.
CubeMap irradiance_cube(const IrradianceField& field, int n, float scale = 1);

// The slow, obviously correct reference.
Rgb irradiance_reference(const CubeMap& radiance, const Vec3d& normal_unit);

// Spherical harmonics of order ≤ 2 (real, in R&H's order: Y00, Y1-1, Y10, Y11, Y2-2, Y2-1, Y20,
// Y21, Y22).
std::array<double, 9> sh9_basis(const Vec3d& d);
struct Sh9 {
  std::array<Rgb, 9> coeff;
};
Sh9 project_sh9(const CubeMap& radiance);
Rgb sh9_irradiance(const Sh9& sh, const Vec3f& normal_unit);

// The exact irradiance at every texel centre of a cube of `size`. Evaluated row by row: on a face,
// n·x is linear in (s, t), so in each texel row the fully visible texels form one run whose sum
// comes from per-row prefix sums of L_i Φ_i (Φ_i Lambert's vector of texel i), and only the one or
// two texels the horizon crosses are clipped. Faces larger than `max_face` are first box-averaged
// to it (equal weights): a fine texel's light then arrives spread over its coarse texel, its
// directions off by at most the coarse texel's diagonal (2√2/max_face rad) and its power by the
// solid angle's variation across it (|∇ ln dΩ/ds dt| ≤ 3/2 on a face: 3√2/max_face), so E is off by
// at most 7.1 ∫ L dω / max_face (5.5 % at 128, the light preview's; on the real HDRIs of ../shared
// 4.6·10⁻⁴ at most: Irradiance.ExactOverReducedFacesWithinItsBound).
// `stop` (core/stop.h) is looked at before each row of texels.
CubeMap exact_irradiance_cube(const CubeMap& radiance, int size, int max_face = 512,
                              const std::atomic<bool>* stop = nullptr);

}  // namespace insitu
