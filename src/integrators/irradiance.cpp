// Integrator `irradiance`: objects shaded by an irradiance field, without visibility.
//
//   L_o(x) = ρ(x) · E(x, n(x)) / π
//
// ρ = Kd × map_Kd(uv) (Lambertian), n the shading normal facing the camera, E one of the
// irradiance modes of irradiance.h: gaussian | sh9 | exact look the cube up by the normal alone;
// volume (light/irradiance_volume.h) also by the position, from SH9 probes of the emitting room
// box and its openings (it needs environment.room_box). No shadows, no occlusion between objects,
// no bounce light: what a real-time engine with a better irradiance than the legacy blur would
// draw. With mode `gaussian` it equals `realtime`.
//
// Parameters:
//   irradiance  the irradiance mode: "gaussian", "sh9", "exact" or "volume" (default "exact"); flat
//               as render.irradiance (DESIGN.md), or render.irradiance.irradiance in its own object.
#include "integrators/registry.h"
#include "light/irradiance.h"
#include "light/irradiance_at.h"

namespace insitu {
namespace {

class IrradianceIntegrator final : public Integrator {
 public:
  IrradianceIntegrator(const RenderInputs& in, IrradianceMode mode)
      : objects_(in.objects), field_(make_irradiance_at(mode, *in.environment, in.room, 32, in.stop)) {}

  CameraSample sample(const Ray& ray, Sampler&) const override {
    CameraSample out;
    if (const auto sp = first_hit(*objects_, ray, out))
      out.radiance = out.albedo * field_->irradiance(sp->p_world, sp->ns_world) / kPiF;
    return out;
  }

 private:
  const EmbreeScene* objects_;
  std::unique_ptr<IrradianceAt> field_;
};

json read_irradiance_params(IntegratorParams& params) {
  IrradianceMode mode = IrradianceMode::kExact;
  if (auto v = params.find("irradiance")) {
    const auto parsed = parse_irradiance_mode(v->string());
    if (!parsed) v->fail("expected " + irradiance_mode_list());
    mode = *parsed;
  }
  return {{"irradiance", irradiance_mode_name(mode)}};
}

std::unique_ptr<Integrator> make_irradiance_integrator(const RenderInputs& inputs, const json& params) {
  return std::make_unique<IrradianceIntegrator>(inputs,
                                                *parse_irradiance_mode(params.at("irradiance").get<std::string>()));
}

}  // namespace

// This integrator's row of the registry (registry.cpp lists the rows).
const IntegratorEntry& irradiance_integrator() {
  static const IntegratorEntry entry{
      "irradiance",
      "Lambertian objects lit by an irradiance mode (render.irradiance), no visibility",
      {/*local_scene*/ false, /*room_box*/ false, /*monte_carlo*/ false, /*reference*/ false, /*legacy*/ false},
      read_irradiance_params,
      make_irradiance_integrator};
  return entry;
}

}  // namespace insitu
