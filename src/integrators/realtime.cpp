// Integrator `realtime`: the legacy real-time path of the 2011 renderer, kept exactly so that
// users can A/B against it.
//
//   colour(x) = base_colour(x) × B(n(x))
//
// base_colour = Kd × map_Kd(uv); n = the interpolated shading normal (facing the camera);
// B = the radiance cube with each face Gaussian-blurred on its own by a kernel as wide as the face
// (gaussian_irradiance.h), looked up along n. No visibility, no shadows, no bounce light, no
// local scene (planes in the scene's local_scene are ignored, as the legacy renderer had none).
//
// Parameters: none (render.spp sets the anti-aliasing samples per pixel).
#include "light/gaussian_irradiance.h"
#include "integrators/registry.h"

namespace insitu {
namespace {

class RealtimeIntegrator final : public Integrator {
 public:
  explicit RealtimeIntegrator(const RenderInputs& in)
      : objects_(in.objects), blurred_(gaussian_blur_faces(*in.environment)) {}

  CameraSample sample(const Ray& ray, Sampler&) const override {
    CameraSample out;
    if (const auto sp = first_hit(*objects_, ray, out)) out.radiance = out.albedo * blurred_.lookup(sp->ns_world);
    return out;
  }

 private:
  const EmbreeScene* objects_;
  CubeMap blurred_;
};

json read_realtime_params(IntegratorParams&) { return json::object(); }

std::unique_ptr<Integrator> make_realtime_integrator(const RenderInputs& inputs, const json&) {
  return std::make_unique<RealtimeIntegrator>(inputs);
}

}  // namespace

// This integrator's row of the registry (registry.cpp lists the rows).
const IntegratorEntry& realtime_integrator() {
  static const IntegratorEntry entry{
      "realtime",
      "legacy real-time path: base colour x face-blurred cube at the normal, no shadows",
      {/*local_scene*/ false, /*room_box*/ false, /*monte_carlo*/ false, /*reference*/ false, /*legacy*/ true},
      read_realtime_params,
      make_realtime_integrator};
  return entry;
}

}  // namespace insitu
