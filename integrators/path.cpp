// Integrator `path`: unidirectional path tracing of the objects, lit by the environment cube, and
// the shadow catcher by differential rendering (Debevec 1998).
//
//   L_o(x, ω_o) = ∫ f(x, ω_o, ω_i) L_i(x, ω_i) cos θ_i dω_i
//
// Objects. At every vertex: next-event estimation toward the environment (EnvSampler: texels in
// proportion to luminance × solid angle, with a shadow ray) and a BSDF sample (cosine-weighted),
// combined by multiple importance sampling with the power heuristic (Veach 1997, §9.2). Escaping
// rays take the cube's nearest texel, the same piecewise-constant function the `exact` irradiance
// integrates. A ray that meets a catcher plane sees the real room: the photo's radiance where the
// point is in the photo's frame (a Lambertian floor looks the same from the object), else the
// cube; such directions are reached by BSDF sampling only (weight 1; the environment sample
// toward them counts as occluded). Russian roulette from the third bounce on, survival
// probability min(0.95, max throughput). Materials: bsdf.h — Lambertian ρ = Kd × map_Kd, plus a
// glossy GGX lobe where the MTL gives Ks (roughness from Ns).
//
// Catcher. A camera sample that meets a catcher plane (local_scene) before any object estimates
// the plane's reflected radiance twice with the same random numbers: with the objects (their
// shadow on the environment sample, and what the BSDF sample sees of them, traced as above) and
// without them. Where no object interferes the two are bitwise equal, so the photo there is left
// exactly as it was. The albedo is the plane's, or, by default, the photo's: ρ = π P / E with E
// the exact irradiance at the plane's normal. One bounce at the catcher: its own light on the
// objects and on itself is already in the photo.
//
// Rays leave a surface from p + n_g·ε with ε = 10⁻⁵·max(1 mm, |p|_∞): an offset relative to the
// position's magnitude, so that objects of a millimetre and of a kilometre are treated alike.
//
// Parameters: render.max_depth (bounces, default 5), render.spp.
// Environment lookups are parallax-corrected when the scene gives environment.room_box.
//
// Not yet (issue 5): catcher meshes (planes only).
#include <algorithm>

#include "bsdf.h"
#include "env_sampling.h"
#include "integrators/integrator.h"

namespace insitu {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

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
      : in_(in), objects_(in.objects), env_(*in.environment), max_depth_(std::max(1, in.max_depth)) {}

  CameraSample sample(const Ray& camera_ray, Sampler& sampler) const override {
    CameraSample out;
    const Hit hit = objects_->intersect(camera_ray);
    float t_plane = 0;
    const int plane = hit_plane(camera_ray, hit.valid() ? hit.t : kInfinity, &t_plane);
    if (plane >= 0) {
      catcher(camera_ray, plane, t_plane, sampler, out);
      return out;
    }
    if (!hit.valid()) return out;
    out.coverage = 1.0f;
    const SurfacePoint sp = objects_->surface(camera_ray, hit);
    out.normal = sp.ns_world;
    out.albedo = sp.material->base_colour(sp.uv);
    out.depth = hit.t;
    out.radiance = trace_from(camera_ray, hit, sampler, 0);
    return out;
  }

 private:
  // The nearest catcher plane the ray meets from its front side within (0, t_max).
  int hit_plane(const Ray& ray, float t_max, float* t_hit) const {
    int best = -1;
    for (std::size_t k = 0; k < in_.planes.size(); ++k) {
      const CatcherPlane& p = in_.planes[k];
      const float dn = ray.dir.dot(p.normal);
      if (!(dn < 0)) continue;
      const float t = (p.point - ray.origin).dot(p.normal) / dn;
      if (t > 0 && t < t_max) { t_max = t; best = int(k); }
    }
    if (best >= 0) *t_hit = t_max;
    return best;
  }

  // The environment's radiance seen from p along dir. With a room box (parallax correction, as in
  // real-time "box-projected" cube maps): the ray meets the box at q, and the cube is looked up
  // toward q from where it was captured, so a point near a window sees more of it.
  Rgb env_radiance(const Vec3f& p, const Vec3f& dir) const {
    if (!in_.room_box) return env_.radiance(dir);
    // Exit point of the box (p inside): the nearest of the slabs the ray leaves through.
    float t_exit = kInfinity;
    for (int k = 0; k < 3; ++k) {
      if (dir[k] == 0) continue;
      const float t = ((dir[k] > 0 ? in_.box_max[k] : in_.box_min[k]) - p[k]) / dir[k];
      t_exit = std::min(t_exit, t);
    }
    if (!(t_exit > 0) || !std::isfinite(t_exit)) return env_.radiance(dir);
    const Vec3f q = p + t_exit * dir - in_.capture;
    return env_.radiance(q.squaredNorm() > 0 ? Vec3f(q.normalized()) : dir);
  }

  // Radiance of the real room at a point of a catcher plane seen along `dir`.
  Rgb room_radiance(const Vec3f& p, const Vec3f& dir) const {
    if (in_.camera && in_.photo_linear) {
      double depth = 0;
      const Vec2d uv = in_.camera->project(p.cast<double>(), &depth);
      if (depth > 0 && uv.x() >= 0 && uv.y() >= 0 && uv.x() < in_.camera->width && uv.y() < in_.camera->height)
        return in_.photo_linear->rgb(int(uv.x()), int(uv.y()));
    }
    return env_radiance(p, dir);
  }

  // Radiance arriving along `ray` (which has hit an object at `hit`), by path tracing.
  Rgb trace_from(Ray ray, Hit hit, Sampler& sampler, int depth) const {
    Rgb throughput = Rgb::Ones(), L = Rgb::Zero();
    for (; depth < max_depth_; ++depth) {
      const SurfacePoint sp = objects_->surface(ray, hit);
      const Bsdf bsdf = Bsdf::from_material(*sp.material, sp.material->base_colour(sp.uv));
      const Frame frame(sp.ns_world);
      const Vec3f wo = frame.to_local(-ray.dir);
      const Vec3f origin = offset_origin(sp.p_world, sp.ng_world);
      // Next-event estimation toward the environment (catcher planes occlude it).
      const float ue = sampler.next(), us = sampler.next(), ut = sampler.next();
      const EnvSample es = env_.sample(ue, us, ut);
      const Vec3f wl = frame.to_local(es.dir);
      float t_dummy = 0;
      if (wl.z() > 0 && es.dir.dot(sp.ng_world) > 0 && hit_plane({origin, es.dir}, kInfinity, &t_dummy) < 0 &&
          !objects_->occluded({origin, es.dir}, 0.0f, kInfinity)) {
        L += throughput * bsdf.eval(wo, wl) * env_radiance(origin, es.dir) *
             (wl.z() / es.pdf * power_heuristic(es.pdf, bsdf.pdf(wo, wl)));
      }
      // BSDF sample.
      BsdfSample bs;
      const float ul = sampler.next(), u1 = sampler.next(), u2 = sampler.next();
      if (!bsdf.sample(wo, ul, u1, u2, &bs)) break;
      const Vec3f wi = frame.to_world(bs.wi);
      if (wi.dot(sp.ng_world) <= 0) break;  // below the geometric surface: no light comes from there
      throughput *= bs.weight;
      ray = {origin, wi};
      hit = objects_->intersect(ray);
      float t_plane = 0;
      if (hit_plane(ray, hit.valid() ? hit.t : kInfinity, &t_plane) >= 0) {
        L += throughput * room_radiance(ray.origin + t_plane * wi, wi);
        break;
      }
      if (!hit.valid()) {
        L += throughput * env_radiance(ray.origin, wi) * power_heuristic(bs.pdf, env_.pdf(wi));
        break;
      }
      if (depth >= 2) {
        const float q = std::min(0.95f, throughput.maxCoeff());
        if (sampler.next() >= q) break;
        throughput /= q;
      }
    }
    return L;
  }

  void catcher(const Ray& camera_ray, int plane_index, float t, Sampler& sampler, CameraSample& out) const {
    const CatcherPlane& plane = in_.planes[std::size_t(plane_index)];
    const Vec3f x = camera_ray.origin + t * camera_ray.dir;
    const Vec3f& n = plane.normal;
    // ρ/π: the plane's, or the photo's P/E.
    Rgb rho_over_pi = plane.albedo / kPiF;
    if (plane.albedo_from_photo) {
      const Rgb P = room_radiance(x, -camera_ray.dir);
      for (int c = 0; c < 3; ++c) rho_over_pi[c] = plane.irradiance[c] > 0 ? P[c] / plane.irradiance[c] : 0.0f;
    }
    const Vec3f origin = offset_origin(x, n);
    Rgb with = Rgb::Zero(), without = Rgb::Zero();
    // Environment sample: blocked by the objects or not.
    const float ue = sampler.next(), us = sampler.next(), ut = sampler.next();
    const EnvSample es = env_.sample(ue, us, ut);
    const float cos_l = n.dot(es.dir);
    if (cos_l > 0) {
      const Rgb c = rho_over_pi * env_radiance(origin, es.dir) * (cos_l / es.pdf * power_heuristic(es.pdf, cos_l / kPiF));
      without += c;
      if (!objects_->occluded({origin, es.dir}, 0.0f, kInfinity)) with += c;
    }
    // BSDF sample: the environment, or what the objects send back.
    const Vec3f wi = cosine_sample(n, sampler.next(), sampler.next());
    const float pdf_bsdf = n.dot(wi) / kPiF;
    const Rgb env_term = kPiF * rho_over_pi * env_radiance(origin, wi) * power_heuristic(pdf_bsdf, env_.pdf(wi));
    without += env_term;
    const Hit hit = objects_->intersect({origin, wi});
    if (hit.valid()) with += kPiF * rho_over_pi * trace_from({origin, wi}, hit, sampler, 1);
    else with += env_term;
    out.with_objects = with;
    out.without_objects = without;
    out.normal = n;
    out.albedo = kPiF * rho_over_pi;
    out.depth = t;
  }

  const RenderInputs in_;
  const EmbreeScene* objects_;
  EnvSampler env_;
  int max_depth_;
};

}  // namespace

std::unique_ptr<Integrator> make_path_integrator(const RenderInputs& inputs) {
  return std::make_unique<PathIntegrator>(inputs);
}

}  // namespace insitu
