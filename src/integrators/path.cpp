// Integrator `path`: unidirectional path tracing of the objects, lit by the environment cube, and
// the shadow catcher by differential rendering (Debevec 1998).
//
//   L_o(x, ω_o) = ∫ f(x, ω_o, ω_i) L_i(x, ω_i) cos θ_i dω_i
//
// Objects. At every vertex: next-event estimation toward the environment (EnvSampler: texels in
// proportion to luminance × solid angle, with a shadow ray) and a BSDF sample (cosine-weighted),
// combined by multiple importance sampling with the power heuristic (Veach 1997, §9.2). Escaping
// rays take the cube's nearest texel, the same piecewise-constant function the `exact` irradiance
// integrates. A ray from an object that meets the local scene sees the real surface as it is with
// the objects present, so that the objects see their own shadows on it, not as the
// photo alone shows it, which holds no shadow of them: it sees P + (W − N), the photo's radiance P
// there (or the room's light along the ray where the photo does not show the point) plus the
// change the objects make, W − N, estimated as for the catcher below (its albedo from the photo, a
// sample of the room's light that the objects can block, one cosine bounce that traces the
// objects). W − N is 0 bit for bit where no object interferes, and P does not depend on the
// surface's albedo, which only scales the change. (A surface whose albedo the scene gives is the
// model's alone: it sees W.) The floor and the meshes of the local scene emit nothing to the room
// light's samples, so directions toward them are reached by BSDF sampling only (weight 1; the
// environment sample toward them counts as occluded). Russian roulette from the third bounce on,
// survival probability min(0.95, max throughput). Materials: bsdf.h — Lambertian ρ = Kd × map_Kd, plus a
// glossy GGX lobe where the MTL gives Ks (roughness from Ns); glTF's, Cycles's Principled BSDF.
//
// Glass. A ray that meets a face from behind (its winding's normal facing away) is inside: the
// glass's index is inverted there, as Cycles does, and the path it took since the last vertex
// crossed the material's Volume Absorption, exp(−σ_a d). A refraction leaves from behind the
// surface, and next-event estimation takes light through the refraction lobe too. Glass blocks
// shadow rays like any object (so do Cycles's): the light that comes through it — the coloured
// shadow of a glass top on the floor, the photo seen through it — is found by BSDF samples, and
// a ray through glass that meets the floor sees the photo there, P + (W − N) as below.
//
// Cut-outs. A shadow ray is attenuated by 1 − a at each surface of alpha a it crosses, as
// Cycles's transparent shadows are (EmbreeScene::transmittance): a sheer surface's shadow, on the
// floor and on the objects, is a fraction of every light sample, not all of some. The camera ray
// crosses up to kSheerLayers sheer surfaces without choosing: each is shaded, weighed by a times
// what the ones before it left, and the rest goes on behind it (sample()), as Cycles weighs the
// Transparent BSDF that alpha mixes in. Past them, and on every later bounce, a traced ray meets
// a surface of alpha a with probability a (stochastic opacity).
//
// Catcher. A camera sample that meets the local scene (a plane or a mesh) before any object estimates
// the plane's reflected radiance twice with the same random numbers: with the objects (their
// shadow on the environment sample, and what the BSDF sample sees of them, traced as above) and
// without them. Where no object interferes the two are bitwise equal, so the photo there is left
// exactly as it was. The albedo is the plane's, or, by default, the photo's: ρ = π P / E with E
// the exact irradiance at the plane's normal; in a room box, the room's irradiance at the point
// (plane_irradiance.h), which varies over the floor (the sun through a window reaches a patch).
// The catcher's own light on the objects and on itself is already in the photo; what the objects
// change there travels on to the other real surfaces (below).
//
// Rays leave a surface from p + n_g·ε with ε = 10⁻⁵·max(1 mm, |p|_∞): an offset relative to the
// position's magnitude, so that objects of a millimetre and of a kilometre are treated alike.
//
// Between real surfaces. The change the objects make at a real surface y, W − N, is itself light
// that reaches every other real surface x: L_with(y) − L_without(y) = Δ(y). So where x's cosine
// sample meets another real surface y (a wall, the floor), `with` adds ρ(x) Δ(y), Δ(y) estimated at
// y as at x, recursively (a path of real bounces; Russian roulette by ρ after the first); `without`
// takes the photo at y as before. One bounce is Debevec's one-bounce catcher. The objects' own
// paths follow the change over catcher_bounces real surfaces (default 5, all that max_depth's
// default allows): the light the objects receive from walls they darken. The photo's pixels take
// it from the change grid: in a room box, Δ(y) is estimated once, before the render, at the nodes
// of a grid over each real surface (each node the mean of change_grid estimates over
// catcher_bounces surfaces, as an object's path takes them), and a pixel's cosine sample that
// meets a real surface y adds ρ(x) Δ(y) read from it. The objects darken the whole room (in a
// small white room by 8 %), which a pixel's own paths find only now and then: speckle all over the
// photo at preview spp, and 2.2–2.7× the render. The grid is smooth and costs a fraction of a
// second; it blurs Δ over a cell (1/64 of the room on a plane, 1/32 on a face), which only the
// second bounce sees (docs/validation.md, "The change grid"). Without a room box, or with
// change_grid 0, the pixels follow it over photo_bounces of their own paths (default 1). Where no
// object interferes Δ is 0 bit for bit, and so is what it adds.
//
// Toward the objects. A real surface's reflection sample is cosine-weighted or, with probability
// toward_objects (less where the objects fill its sky), drawn in the cones of the objects'
// bounding spheres, and weighed by the mixture's density (render/object_cones.h): a wall far from
// the furniture finds it in every other sample instead of one in fifty, so its change W − N is no
// longer a few lucky hits (speckle over the whole photo at preview spp). The estimate's mean is
// the same; N is estimated from the same mixture.
//
// Parameters:
//   max_depth  bounces, 1 … 1000 (default 5); flat as render.max_depth, or render.path.max_depth.
//   catcher_bounces  real surfaces an object's path follows the objects' change over, 1 … 1000
//              (default 5), within max_depth.
//   photo_bounces  the same for the photo's pixels (a camera ray that meets a real surface),
//              1 … 1000 (default 1), where the change grid does not serve them.
//   change_grid  estimates of Δ at each node of the change grid, 0 … 4096 (default 64; 0: off).
//   toward_objects  the share of a real surface's reflection samples drawn toward the objects,
//              0 … 0.9 (default 0.5; 0: the cosine alone).
// With environment.room_box the room is an emitting box (room_light.h): its faces carry the cube's
// radiance projected from the capture point, and next-event estimation samples them as an area
// light, with the pdf converted to solid angle at the shading point and MIS against the BSDF.
// Its openings let distant light in (the sun through a window), sampled as portals. Its walls
// (every face but the openings) are local-scene surfaces too: a camera ray
// that meets a wall catches the objects' shadows and light there like the floor, with ρ from the
// photo and the wall's irradiance grid; an object's ray that meets a wall sees the emitter's
// radiance, weighed by MIS against the room light's samples of it, plus the change W − N the
// objects make there (weight 1: only BSDF samples find it). The room light's own samples are not
// blocked by the walls they land on. A plane lying on a wall (the floor) takes precedence. ρ ≤ 1:
// a photo brighter than a white surface would be there is emission (a ceiling lamp), which the
// objects cannot shadow.
//
// The local scene may hold meshes too (a real table, a step): they catch shadows like the planes
// (with E(n) from the exact irradiance cube), block the environment for the objects, and show the
// photo to them.
#include <algorithm>
#include <array>

#include "core/sampling.h"
#include "core/stop.h"
#include "integrators/registry.h"
#include "render/bsdf.h"
#include "render/object_cones.h"
#include "render/shading_normal.h"
#include "light/env_sampling.h"
#include "light/plane_grid.h"
#include "light/plane_irradiance.h"
#include "light/room_light.h"

namespace insitu {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr int kSheerLayers = 16;  // the sheer surfaces a camera ray crosses, at most, before it chooses

class PathIntegrator final : public Integrator {
 public:
  PathIntegrator(const RenderInputs& in, int max_depth, int catcher_bounces, int photo_bounces, float toward_objects,
                 int change_grid)
      : in_(in),
        objects_(in.objects),
        cones_(in.objects->meshes()),
        cache_(room_cache(in)),
        room_light_(room_light(*cache_, in.stop)),
        room_(*room_light_),
        max_depth_(std::max(1, max_depth)),
        catcher_bounces_(std::max(1, catcher_bounces)),
        photo_bounces_(std::max(1, photo_bounces)),
        toward_objects_(std::clamp(toward_objects, 0.0f, 0.9f)) {
    // In a room box the irradiance behind a photo-derived albedo varies over the plane.
    if (!in_.room) return;
    for (const CatcherPlane& p : in_.planes)
      plane_irradiance_.push_back(p.albedo_from_photo ? cache_->plane(p.point, p.normal, 64, in.stop) : nullptr);
    // The box's faces catch too (by face: +x, −x, +y, −y, +z, −z; normals into the room).
    for (int face = 0; face < 6; ++face) {
      const FacePlane f = face_plane(*in_.room, face);
      wall_irradiance_[std::size_t(face)] = cache_->plane(f.point, f.normal, 32, in.stop);
    }
    if (change_grid > 0 && !objects_->meshes().empty()) build_change_grids(change_grid, in.stop);
  }

  static std::shared_ptr<const RoomLight> room_light(RoomCache& cache, const std::atomic<bool>* stop) {
    throw_if_stopped(stop);
    return cache.light();
  }

  // The room's cache when the caller shares one of this room (a batch's entries), else our own.
  static std::shared_ptr<RoomCache> room_cache(const RenderInputs& in) {
    if (in.room_cache && in.room_cache->serves(*in.environment, in.room)) return in.room_cache;
    return std::make_shared<RoomCache>(*in.environment, in.room);
  }

  // The camera ray crosses the sheer surfaces it meets (cut-outs of opacity 0 < a < 1) rather
  // than choosing one: each covers a share r·a of the pixel's sample (r what the surfaces before
  // it left), shaded as present, and what lies behind is seen through the rest, r·(1 − a): an
  // opaque object, the real room (its W and N scaled by r, which the composite's (1 − α) P W/N
  // and (1 − α) P + W − N both take as the room seen through the sheer share), or the photo
  // (1 − α). kSheerLayers of them at most; past them the stochastic choice.
  CameraSample sample(const Ray& camera_ray, Sampler& sampler) const override {
    CameraSample out;
    Ray ray = camera_ray;
    float r = 1, coverage = 0;
    Rgb objects = Rgb::Zero();  // premultiplied by coverage
    for (int layer = 0;; ++layer) {
      const Hit hit = layer < kSheerLayers ? objects_->intersect_sheer(ray) : objects_->intersect(ray);
      const CatcherHit c = find_catcher(ray, hit.valid() ? hit.t : kInfinity, /*walls=*/true);
      if (c.valid) {
        CameraSample behind;
        catcher(ray, c, sampler, behind);
        out.with_objects = r * behind.with_objects, out.without_objects = r * behind.without_objects;
        if (layer == 0) out.normal = behind.normal, out.albedo = behind.albedo, out.depth = behind.depth;
        break;
      }
      if (!hit.valid()) break;
      const SurfacePoint sp = objects_->surface(ray, hit);
      if (layer == 0) out.normal = sp.ns_world, out.albedo = sp.material->base_colour(sp.uv), out.depth = hit.t;
      // Past kSheerLayers the surface met was chosen with probability a: it is there, whole.
      const bool sheer = layer < kSheerLayers && sp.material->cutout();
      const float a = sheer ? std::min(1.0f, sp.material->opacity(sp.uv)) : 1.0f;
      objects += r * trace_from(ray, hit, sampler, 0, a);
      coverage += r * a;
      r *= 1 - a;
      if (!(r > 0)) break;
      ray = {offset_origin(sp.p_world, -sp.ng_world), ray.dir};
    }
    out.coverage = coverage;
    if (coverage > 0) out.radiance = objects / coverage;
    return out;
  }

 private:
  // The nearest catcher plane the ray meets from its front side within (0, t_max). With a room
  // box the real floor ends at the room's walls: hits outside the box are not hits.
  int hit_plane(const Ray& ray, float t_max, float* t_hit) const {
    int best = -1;
    for (std::size_t k = 0; k < in_.planes.size(); ++k) {
      const CatcherPlane& p = in_.planes[k];
      const float dn = ray.dir.dot(p.normal);
      if (!(dn < 0)) continue;
      const float t = (p.point - ray.origin).dot(p.normal) / dn;
      if (!(t > 0 && t < t_max) || !inside_room(ray.origin + t * ray.dir)) continue;
      t_max = t;
      best = int(k);
    }
    if (best >= 0) *t_hit = t_max;
    return best;
  }

  // Inside the room box, with a tolerance of 10⁻⁴ of its size (a floor plane lies on its face).
  bool inside_room(const Vec3f& x) const {
    if (!in_.room) return true;
    const Vec3f slack = 1e-4f * (in_.room->max - in_.room->min);
    return (x.array() >= (in_.room->min - slack).array()).all() && (x.array() <= (in_.room->max + slack).array()).all();
  }

  // What a ray meets first of the local scene within (0, t_max): a plane (from its front) or a
  // catcher mesh (either side; the normal turned toward the ray).
  struct CatcherHit {
    bool valid = false;
    float t = 0;
    Vec3f x = Vec3f::Zero(), n = Vec3f::Zero();
    bool albedo_from_photo = true;
    Rgb albedo = Rgb::Zero(), irradiance = Rgb::Zero();
    bool wall = false;  // a face of the room box: also the room's emitter
    int surface = -1;   // its change grid: a plane's index, the box's faces after them; -1: none
  };
  // A wall of the room box (not an opening) that a ray from inside the box leaves through, before
  // t_max: the real walls catch the objects' shadows and light like the floor.
  bool hit_wall(const Ray& ray, float t_max, CatcherHit* c) const {
    float t = 0;
    int axis = 0;
    if (!in_.room || !room_.inside(ray.origin) || !room_.exit(ray.origin, ray.dir, &t, &axis) || !(t < t_max))
      return false;
    const int face = box_face(axis, ray.dir[axis] > 0);
    const FacePlane f = face_plane(*in_.room, face);
    Vec3f x = ray.origin + t * ray.dir;
    x[axis] = f.point[axis];
    if (room_.openings_at(x, axis) > 0) return false;
    const PlaneIrradiance& grid = *wall_irradiance_[std::size_t(face)];
    *c = {true, t, x, f.normal, true, Rgb::Zero(), grid.at(x), true};
    c->surface = int(in_.planes.size()) + face;
    return true;
  }

  CatcherHit find_catcher(const Ray& ray, float t_max, bool walls = false) const {
    CatcherHit c;
    float t = 0;
    const int k = hit_plane(ray, t_max, &t);
    if (k >= 0) {
      const CatcherPlane& p = in_.planes[std::size_t(k)];
      const Vec3f x = ray.origin + t * ray.dir;
      const PlaneIrradiance* grid = plane_irradiance_.empty() ? nullptr : plane_irradiance_[std::size_t(k)].get();
      c = {true, t, x, p.normal, p.albedo_from_photo, p.albedo, grid ? grid->at(x) : p.irradiance};
      c.surface = k;
      t_max = t;
    }
    if (in_.catcher_meshes && !in_.catcher_meshes->empty()) {
      const Hit h = in_.catcher_meshes->intersect(ray, 0.0f, t_max);
      if (h.valid()) {
        const SurfacePoint sp = in_.catcher_meshes->surface(ray, h);
        const CatcherMesh& info = in_.catcher_mesh_info[std::size_t(h.mesh)];
        c = {true,
             h.t,
             sp.p_world,
             sp.ng_world,
             info.albedo_from_photo,
             info.albedo,
             in_.catcher_irradiance->irradiance(sp.ng_world)};
      }
    }
    // A wall behind a plane that lies on it (the floor on the box's floor) is the plane.
    if (CatcherHit w; walls && hit_wall(ray, (c.valid ? c.t : t_max) * (1 - 1e-4f), &w)) c = w;
    return c;
  }

  // The room's light seen from p along dir (room_light.h): with a room box, the box's faces emit
  // what the capture point saw toward them, so a point near a window sees more of it.
  Rgb env_radiance(const Vec3f& p, const Vec3f& dir) const { return room_.radiance(p, dir); }
  // The same, found by a BSDF sample of density pdf_bsdf: weighed by MIS against the room light's
  // samples (one lookup for the radiance and the light's density).
  Rgb room_light_mis(const Vec3f& p, const Vec3f& dir, float pdf_bsdf) const {
    const RoomLookup l = room_.lookup(p, dir);
    return l.radiance * power_heuristic(pdf_bsdf, l.pdf);
  }

  // Whether the room's light sampled from `origin` reaches it: the local scene blocks it for
  // everything (its light is reached by BSDF samples only, weight 1; a sample on the floor face
  // meets the floor plane at its own distance), the objects only with them.
  bool blocked_by_catcher(const Vec3f& origin, const RoomSample& rs) const {
    const float t_max = std::isfinite(rs.distance) ? rs.distance * (1 + 1e-3f) : kInfinity;
    return find_catcher({origin, rs.dir}, t_max).valid;
  }
  // The share of that light the objects let through: 0 behind an opaque one, 1 − a through a
  // cut-out surface of opacity a (EmbreeScene::transmittance), exactly 1 where none is in the way.
  float through_objects(const Vec3f& origin, const RoomSample& rs) const {
    return objects_->transmittance({origin, rs.dir}, 0.0f, std::isfinite(rs.distance) ? rs.distance : kInfinity);
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

  // Radiance arriving along `ray` (which has hit an object at `hit`), by path tracing. With
  // `presence` a < 1 the first surface is a sheer one, and what is returned is a times its
  // radiance: its emission and light sample weighed by a, and its BSDF sample taken with
  // probability a, as Cycles samples the Transparent BSDF that alpha mixes in.
  Rgb trace_from(Ray ray, Hit hit, Sampler& sampler, int depth, float presence = 1) const {
    Rgb throughput = Rgb::Ones(), L = Rgb::Zero();
    for (; depth < max_depth_; ++depth, presence = 1) {
      const SurfacePoint sp = objects_->surface(ray, hit);
      // A ray that leaves a glass through its back face has crossed its volume (Beer–Lambert).
      if (sp.backfacing) throughput *= absorbed(*sp.material, (sp.p_world - ray.origin).norm());
      // Emission (glTF's emissive), found by the camera or a BSDF sample only: emitting objects
      // are not sampled as lights.
      L += presence * throughput * sp.material->emitted(sp.uv);
      Bsdf bsdf = Bsdf::from_material(*sp.material, sp.uv, sp.backfacing);
      // Cycles bends every closure's normal so that its mirror direction stays above the surface,
      // and shadows the diffuse where that normal is not the smooth one.
      const Vec3f n_closure = valid_reflection_normal(sp.ng_world, -ray.dir, sp.ns_world);
      const Frame frame(n_closure);
      if (n_closure != sp.n_smooth_world) bsdf.set_smooth_normal(frame.to_local(sp.n_smooth_world));
      // The clear coat has its own normal: the smooth one where a normal map bends the rest, or its
      // own map's (render/bsdf.h).
      if (sp.material->clearcoat > 0 && sp.n_coat_world != sp.ns_world) {
        const Vec3f n_coat = valid_reflection_normal(sp.ng_world, -ray.dir, sp.n_coat_world);
        if (n_coat != n_closure) bsdf.set_coat_normal(frame.to_local(n_coat).normalized());
      }
      const Vec3f wo = frame.to_local(-ray.dir);
      // Rays leave from the side they go to: a refraction from behind the surface.
      const Vec3f origin = offset_origin(sp.p_world, sp.ng_world);
      const Vec3f origin_behind = offset_origin(sp.p_world, -sp.ng_world);
      L += presence * throughput * next_event(sp, bsdf, frame, wo, origin, origin_behind, sampler);
      if (presence < 1 && !(sampler.next() < presence)) break;  // taken with probability a: weight a / a
      // BSDF sample.
      BsdfSample bs;
      const float ul = sampler.next(), u1 = sampler.next(), u2 = sampler.next();
      if (!bsdf.sample(wo, ul, u1, u2, &bs)) break;
      const Vec3f wi = frame.to_world(bs.wi);
      const bool refracted = bs.wi.z() < 0;
      if ((wi.dot(sp.ng_world) <= 0) != refracted) break;  // the geometric side disagrees: no light comes
      throughput *= bs.weight;
      ray = {refracted ? origin_behind : origin, wi};
      hit = objects_->intersect(ray);
      if (const CatcherHit c = find_catcher(ray, hit.valid() ? hit.t : kInfinity, /*walls=*/true); c.valid) {
        // The real surface as photographed, changed by the objects (differential rendering once
        // more): they see their own shadows and light on it. A wall is the room's emitter too:
        // its light is weighed against the room light's samples of it.
        const CatcherEstimate e = estimate_catcher(c, wi, sampler, depth, catcher_bounces_);
        const Rgb photo = c.wall ? room_light_mis(ray.origin, wi, bs.pdf) : room_radiance(c.x, wi);
        L += throughput * (c.albedo_from_photo ? Rgb(photo + e.change) : e.with());
        break;
      }
      if (!hit.valid()) {
        L += throughput * room_light_mis(ray.origin, wi, bs.pdf);
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

  // Cycles's Volume Absorption inside a glass: exp(−σ_a d) over a path of d metres.
  static Rgb absorbed(const Material& m, float d_m) {
    if (!(m.absorption.maxCoeff() > 0)) return Rgb::Ones();
    return (-m.absorption * d_m).exp();
  }

  // Next-event estimation toward the room's light (catcher planes occlude it), weighed by MIS
  // against the BSDF; through a glass's refraction, from behind the surface.
  Rgb next_event(const SurfacePoint& sp, const Bsdf& bsdf, const Frame& frame, const Vec3f& wo, const Vec3f& origin,
                 const Vec3f& origin_behind, Sampler& sampler) const {
    const float ue = sampler.next(), us = sampler.next(), ut = sampler.next();
    const RoomSample rs = room_.sample(origin, ue, us, ut);
    const Vec3f wl = frame.to_local(rs.dir);
    const bool behind = wl.z() < 0;  // only a glass's refraction takes light from behind
    if (!(rs.pdf > 0) || wl.z() == 0 || (behind && !bsdf.transmits()) || (rs.dir.dot(sp.ng_world) > 0) == behind)
      return Rgb::Zero();
    const Vec3f& from = behind ? origin_behind : origin;
    if (blocked_by_catcher(from, rs)) return Rgb::Zero();
    const float through = through_objects(from, rs);
    if (!(through > 0)) return Rgb::Zero();
    return bsdf.eval(wo, wl) * rs.radiance *
           (through * std::abs(wl.z()) / rs.pdf * power_heuristic(rs.pdf, bsdf.pdf(wo, wl)));
  }

  // ρ/π of a local-scene point met along `dir`: the surface's, or the photo's P/E (E the room's
  // irradiance there without objects), P where the photo sees the point, else the room's light
  // along `dir` (what the capture point saw in that direction: the real surface beyond). ρ is at
  // most 1: radiance beyond what a white surface reflects is emission (a lamp in the ceiling), which
  // the objects cannot shadow and must not be reflected as if it were an albedo of 100.
  Rgb albedo_over_pi(const CatcherHit& c, const Vec3f& dir) const {
    if (!c.albedo_from_photo) return c.albedo / kPiF;
    const Rgb P = room_radiance(c.x, dir);
    Rgb rho_over_pi;
    for (int k = 0; k < 3; ++k)
      rho_over_pi[k] = c.irradiance[k] > 0 ? std::min(P[k] / c.irradiance[k], 1.0f / kPiF) : 0.0f;
    return rho_over_pi;
  }

  // The radiance a real surface reflects along -dir, without the objects (N) and the change they
  // make (Δ = W − N), from the same random numbers:
  //   L(x) = ρ/π ∫ L_room(ω) V(x, ω) cos θ dω
  // estimated by a sample of the room's light (blocked by the local scene for both, by the
  // objects only with them) and a cosine-weighted sample combined by MIS. The cosine sample traces
  // an object it meets (depth + 1: the objects' light on the real surface), and takes what lies
  // behind otherwise: the real room as the photo shows it, or the room's light, and beyond a real
  // surface its own change (change_beyond). For the model — a Lambertian real surface of albedo ρ
  // lit by the room — W = N + Δ is unbiased; N has mean ρ/π E = P, the photo. Δ gathers only the
  // terms where the objects interfere, so it is 0 bit for bit where none does. `base`: N is wanted
  // too; a further real bounce wants Δ alone, and skips the lookups only N needs.
  struct CatcherEstimate {
    Rgb without = Rgb::Zero(), change = Rgb::Zero(), rho_over_pi = Rgb::Zero();
    Rgb with() const { return without + change; }
  };
  CatcherEstimate estimate_catcher(const CatcherHit& c, const Vec3f& dir, Sampler& sampler, int depth, int bounces,
                                   bool base = true, bool from_grid = false) const {
    CatcherEstimate e;
    e.rho_over_pi = albedo_over_pi(c, dir);
    const Vec3f& n = c.n;
    const Vec3f origin = offset_origin(c.x, n);
    const ReflectedSampling reflected(cones_, toward_objects_, origin, n);
    const float ue = sampler.next(), us = sampler.next(), ut = sampler.next();
    const RoomSample rs = room_.sample(origin, ue, us, ut);
    const float cos_l = n.dot(rs.dir);
    if (rs.pdf > 0 && cos_l > 0) {
      const float blocked = 1 - through_objects(origin, rs);  // exactly 0 where no object is in the way
      if ((base || blocked > 0) && !blocked_by_catcher(origin, rs)) {
        const Rgb contribution =
            e.rho_over_pi * rs.radiance * (cos_l / rs.pdf * power_heuristic(rs.pdf, reflected.pdf(rs.dir)));
        if (base) e.without += contribution;
        if (blocked > 0) e.change -= blocked * contribution;
      }
    }
    const float uc = sampler.next(), u1 = sampler.next(), u2 = sampler.next();
    const Vec3f wi = reflected.sample(uc, u1, u2);
    const float pdf_wi = reflected.pdf(wi);
    if (!(n.dot(wi) > 0) || !(pdf_wi > 0)) return e;  // a cone's direction below the surface: no light
    // The cosine sample's estimate times (cos θ / π) / p(ω): 1 bit for bit without cones.
    const float scale = n.dot(wi) / kPiF / pdf_wi;
    const Hit hit = objects_->intersect({origin, wi});
    const CatcherHit behind_hit = find_catcher({origin, wi}, kInfinity);
    const bool object_first = hit.valid() && (!behind_hit.valid || hit.t < behind_hit.t);
    if (base || object_first) {
      Rgb behind;
      if (behind_hit.valid) {
        behind = kPiF * e.rho_over_pi * room_radiance(behind_hit.x, wi) * scale;
      } else {
        const RoomLookup l = room_.lookup(origin, wi);
        behind = kPiF * e.rho_over_pi * l.radiance * (scale * power_heuristic(pdf_wi, l.pdf));
      }
      if (base) e.without += behind;
      if (object_first)
        e.change += kPiF * e.rho_over_pi * trace_from({origin, wi}, hit, sampler, depth + 1) * scale - behind;
    }
    if (!object_first && from_grid)
      e.change += scale * kPiF * e.rho_over_pi * grid_change({origin, wi}, hit);
    else if (!object_first && bounces > 1 && depth + 1 < max_depth_)
      e.change += scale * change_beyond(e.rho_over_pi, origin, wi, hit, sampler, depth, bounces, base);
    return e;
  }

  // ρ(x) Δ(y): the objects' change at the real surface y that x's cosine sample meets (a wall
  // included), estimated there; 0 where it meets none. Past the first real bounce a path goes on
  // with probability max ρ(x).
  Rgb change_beyond(const Rgb& rho_over_pi, const Vec3f& origin, const Vec3f& wi, const Hit& hit, Sampler& sampler,
                    int depth, int bounces, bool first) const {
    const CatcherHit y = find_catcher({origin, wi}, hit.valid() ? hit.t : kInfinity, /*walls=*/true);
    if (!y.valid) return Rgb::Zero();
    float q = 1;
    if (!first) {
      q = std::min(1.0f, kPiF * rho_over_pi.maxCoeff());
      if (!(sampler.next() < q)) return Rgb::Zero();
    }
    const CatcherEstimate d = estimate_catcher(y, wi, sampler, depth + 1, bounces - 1, /*base=*/false);
    return kPiF * rho_over_pi * d.change / q;
  }

  // Δ(y) from the change grid at the real surface y the ray meets before `hit`; 0 where it meets none.
  Rgb grid_change(const Ray& ray, const Hit& hit) const {
    const CatcherHit y = find_catcher(ray, hit.valid() ? hit.t : kInfinity, /*walls=*/true);
    if (!y.valid || y.surface < 0 || change_[std::size_t(y.surface)].nodes() == 0) return Rgb::Zero();
    return change_[std::size_t(y.surface)].at(y.x);
  }

  // The change grid: Δ(y) at the nodes of a grid over each real surface (the planes' 64 cells to
  // the box, the faces' 32), each the mean of `samples` estimates over catcher_bounces real
  // surfaces, as an object's path takes it.
  void build_change_grids(int samples, const std::atomic<bool>* stop) {
    change_.resize(in_.planes.size() + 6);
    for (std::size_t s = 0; s < change_.size(); ++s) {
      CatcherHit c;
      if (!change_surface(s, &c, &change_[s])) continue;
      change_[s].fill([&](const Vec3f& x, std::uint64_t key) { return change_at(c, s, x, key, samples); }, stop);
    }
  }

  // Surface s of the change grid (a plane, or a face of the box after them) as a catcher hit
  // without its point, and its grid; false for a face that a plane lies on (the floor's).
  bool change_surface(std::size_t s, CatcherHit* c, PlaneGrid* grid) const {
    const std::size_t planes = in_.planes.size();
    Vec3f point = Vec3f::Zero(), normal = Vec3f::Zero();
    c->valid = true;
    if (s < planes) {
      const CatcherPlane& p = in_.planes[s];
      point = p.point, normal = p.normal, c->albedo_from_photo = p.albedo_from_photo, c->albedo = p.albedo;
    } else {
      const FacePlane f = face_plane(*in_.room, int(s - planes));
      point = f.point, normal = f.normal;
      c->wall = true;
      for (const CatcherPlane& p : in_.planes)
        if (p.normal.dot(normal) > 0.999f && std::abs((p.point - point).dot(normal)) < 1e-3f) return false;
    }
    c->n = normal.normalized();
    *grid = PlaneGrid(*in_.room, point, normal, s < planes ? 64 : 32);
    return true;
  }

  // Δ at point x of surface s: the mean of `samples` estimates, as at a real surface an object's
  // ray meets straight on.
  Rgb change_at(CatcherHit c, std::size_t s, const Vec3f& x, std::uint64_t key, int samples) const {
    const std::size_t planes = in_.planes.size();
    c.x = x;
    if (s >= planes)
      c.irradiance = wall_irradiance_[s - planes]->at(x);
    else if (!plane_irradiance_.empty() && plane_irradiance_[s])
      c.irradiance = plane_irradiance_[s]->at(x);
    else
      c.irradiance = in_.planes[s].irradiance;
    Rgb sum = Rgb::Zero();
    for (int k = 0; k < samples; ++k) {
      Sampler sampler(0xC4A96E6D1Dull, (std::uint64_t(s) << 40) + key, std::uint64_t(k));
      sum += estimate_catcher(c, -c.n, sampler, 0, catcher_bounces_, /*base=*/false).change;
    }
    return sum / float(samples);
  }

  void catcher(const Ray& camera_ray, const CatcherHit& c, Sampler& sampler, CameraSample& out) const {
    const CatcherEstimate e =
        estimate_catcher(c, camera_ray.dir, sampler, 0, photo_bounces_, /*base=*/true, !change_.empty());
    out.with_objects = e.with();
    out.without_objects = e.without;
    out.normal = c.n;
    out.albedo = kPiF * e.rho_over_pi;
    out.depth = c.t;
  }

  const RenderInputs in_;
  const EmbreeScene* objects_;
  ObjectCones cones_;  // the objects' bounding spheres, toward which real surfaces sample too
  std::shared_ptr<RoomCache> cache_;
  std::shared_ptr<const RoomLight> room_light_;
  const RoomLight& room_;
  int max_depth_;
  int catcher_bounces_, photo_bounces_;
  float toward_objects_;                                                   // s_0 of object_cones.h's ReflectedSampling
  std::vector<std::shared_ptr<const PlaneIrradiance>> plane_irradiance_;   // by plane, with a room box
  std::array<std::shared_ptr<const PlaneIrradiance>, 6> wall_irradiance_;  // by face of the room box
  std::vector<PlaneGrid> change_;  // Δ by CatcherHit::surface, with change_grid; empty: photo_bounces' paths
};

json read_path_params(IntegratorParams& params) {
  int max_depth = 5, catcher_bounces = 5, photo_bounces = 1;
  double toward_objects = 0.5;
  int change_grid = 64;
  if (auto v = params.find("max_depth")) max_depth = int(v->integer(1, 1000));
  if (auto v = params.find("catcher_bounces")) catcher_bounces = int(v->integer(1, 1000));
  if (auto v = params.find("photo_bounces")) photo_bounces = int(v->integer(1, 1000));
  if (auto v = params.find("toward_objects")) toward_objects = v->number(0, 0.9);
  if (auto v = params.find("change_grid")) change_grid = int(v->integer(0, 4096));
  return {{"max_depth", max_depth},
          {"catcher_bounces", catcher_bounces},
          {"photo_bounces", photo_bounces},
          {"toward_objects", toward_objects},
          {"change_grid", change_grid}};
}

std::unique_ptr<Integrator> make_path_integrator(const RenderInputs& inputs, const json& params) {
  return std::make_unique<PathIntegrator>(
      inputs, params.at("max_depth").get<int>(), params.at("catcher_bounces").get<int>(),
      params.at("photo_bounces").get<int>(), params.at("toward_objects").get<float>(),
      params.at("change_grid").get<int>());
}

}  // namespace

// This integrator's row of the registry (registry.cpp lists the rows).
const IntegratorEntry& path_integrator() {
  static const IntegratorEntry entry{
      "path",
      "path tracing of the objects with environment importance sampling and MIS (shadows between objects)",
      {/*local_scene*/ true, /*room_box*/ true, /*monte_carlo*/ true, /*reference*/ true, /*legacy*/ false},
      read_path_params,
      make_path_integrator};
  return entry;
}

}  // namespace insitu
