// Integrator `irradiance`: objects shaded by an irradiance field, without visibility.
//
//   L_o(x) = ρ(x) · E(n(x)) / π
//
// ρ = Kd × map_Kd(uv) (Lambertian), n the shading normal facing the camera, E one of the
// irradiance modes of irradiance.h chosen by the scene's render.irradiance (gaussian | sh9 |
// exact). No shadows, no occlusion between objects, no bounce light: what a real-time engine with
// a better irradiance than the legacy blur would draw. With mode `gaussian` it equals `realtime`.
//
// Parameters: render.irradiance (default "exact").
#include "integrators/integrator.h"
#include "irradiance.h"

namespace insitu {
namespace {

class IrradianceIntegrator final : public Integrator {
 public:
  explicit IrradianceIntegrator(const RenderInputs& in)
      : objects_(in.objects), field_(make_irradiance(in.irradiance_mode, *in.environment)) {}

  CameraSample sample(const Ray& ray, Sampler&) const override {
    CameraSample out;
    if (const auto sp = first_hit(*objects_, ray, out)) out.radiance = out.albedo * field_->irradiance(sp->ns_world) / kPiF;
    return out;
  }

 private:
  const EmbreeScene* objects_;
  std::unique_ptr<IrradianceField> field_;
};

}  // namespace

std::unique_ptr<Integrator> make_irradiance_integrator(const RenderInputs& inputs) {
  return std::make_unique<IrradianceIntegrator>(inputs);
}

}  // namespace insitu
