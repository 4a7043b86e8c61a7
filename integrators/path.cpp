// Integrator `path`: unidirectional path tracing of the objects, lit by the environment cube.
//
//   L_o(x, ω_o) = ∫ f(x, ω_o, ω_i) L_i(x, ω_i) cos θ_i dω_i
//
// At every vertex: next-event estimation toward the environment (EnvSampler: texels in proportion
// to luminance × solid angle, with a shadow ray) and a BSDF sample (cosine-weighted), combined by
// multiple importance sampling with the power heuristic (Veach 1997, §9.2); escaping rays take the
// environment's radiance as the cube's nearest texel, the same piecewise-constant function the
// `exact` irradiance integrates. Russian roulette from the third bounce on, survival probability
// min(0.95, max throughput). Materials: Lambertian, ρ = Kd × map_Kd.
//
// Rays leave a surface from p + n_g·ε with ε = 10⁻⁵·max(1 mm, |p|_∞): an offset relative to the
// position's magnitude, so that objects of a millimetre and of a kilometre are treated alike.
//
// Parameters: render.max_depth (bounces, default 5), render.spp.
// Not yet (issue 5): the glossy GGX lobe, the local scene (catcher planes), differential rendering.
#include <algorithm>

#include "env_sampling.h"
#include "integrators/integrator.h"

namespace insitu {
namespace {

// Cosine-weighted direction about n (Malley's method), pdf = cos θ / π.
Vec3f cosine_sample(const Vec3f& n, float u1, float u2) {
  const Vec3f t = (std::abs(n.x()) < 0.9f ? Vec3f(1, 0, 0) : Vec3f(0, 1, 0)).cross(n).normalized();
  const Vec3f b = n.cross(t);
  const float r = std::sqrt(u1), phi = 2 * kPiF * u2;
  return (r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0f, 1 - u1)) * n).normalized();
}

float power_heuristic(float a, float b) { return a * a / (a * a + b * b); }

Vec3f offset_origin(const Vec3f& p, const Vec3f& ng) {
  const float eps = 1e-5f * std::max(1e-3f, p.cwiseAbs().maxCoeff());
  return p + eps * ng;
}

class PathIntegrator final : public Integrator {
 public:
  explicit PathIntegrator(const RenderInputs& in)
      : objects_(in.objects), env_(*in.environment), max_depth_(std::max(1, in.max_depth)) {}

  CameraSample sample(const Ray& camera_ray, Sampler& sampler) const override {
    CameraSample out;
    Hit hit = objects_->intersect(camera_ray);
    if (!hit.valid()) return out;
    out.coverage = 1.0f;
    Ray ray = camera_ray;
    Rgb throughput = Rgb::Ones(), L = Rgb::Zero();
    for (int depth = 0; depth < max_depth_; ++depth) {
      const SurfacePoint sp = objects_->surface(ray, hit);
      const Rgb albedo = sp.material->base_colour(sp.uv);
      const Vec3f& n = sp.ns_world;
      const Vec3f origin = offset_origin(sp.p_world, sp.ng_world);
      // Next-event estimation toward the environment.
      const float ue = sampler.next(), us = sampler.next(), ut = sampler.next();
      const EnvSample es = env_.sample(ue, us, ut);
      const float cos_l = n.dot(es.dir);
      if (cos_l > 0 && es.dir.dot(sp.ng_world) > 0 && !objects_->occluded({origin, es.dir}, 0.0f, kInfinity)) {
        const float pdf_bsdf = cos_l / kPiF;
        L += throughput * albedo / kPiF * es.radiance * (cos_l / es.pdf * power_heuristic(es.pdf, pdf_bsdf));
      }
      // BSDF sample: f·cos/pdf = ρ for a Lambertian surface.
      const Vec3f wi = cosine_sample(n, sampler.next(), sampler.next());
      if (wi.dot(sp.ng_world) <= 0) break;  // below the geometric surface: no light comes from there
      const float pdf_bsdf = n.dot(wi) / kPiF;
      throughput *= albedo;
      ray = {origin, wi};
      hit = objects_->intersect(ray);
      if (!hit.valid()) {
        L += throughput * env_.radiance(wi) * power_heuristic(pdf_bsdf, env_.pdf(wi));
        break;
      }
      if (depth >= 2) {
        const float q = std::min(0.95f, throughput.maxCoeff());
        if (sampler.next() >= q) break;
        throughput /= q;
      }
    }
    out.radiance = L;
    return out;
  }

 private:
  static constexpr float kInfinity = std::numeric_limits<float>::infinity();
  const EmbreeScene* objects_;
  EnvSampler env_;
  int max_depth_;
};

}  // namespace

std::unique_ptr<Integrator> make_path_integrator(const RenderInputs& inputs) {
  return std::make_unique<PathIntegrator>(inputs);
}

}  // namespace insitu
