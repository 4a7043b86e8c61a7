#include "render/embree_scene.h"

#include <embree3/rtcore.h>

#include <stdexcept>
#include <string>
#include <fmt/format.h>

#include "render/cutouts.h"
#include "render/ray_log.h"
#include "render/shading_normal.h"

namespace insitu {

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::string error;     // the first error Embree reported, if any
  bool cutouts = false;  // some mesh has a cut-out material: queries carry render/cutouts.h's filters
};

namespace {
// Embree reports programming errors and out-of-memory here: the first is kept, and building the
// scene then fails with it (an internal error, exit code 1), instead of rendering from a scene
// that is not what was asked for.
void embree_error(void* user, RTCError code, const char* str) {
  auto* impl = static_cast<EmbreeScene::Impl*>(user);
  if (impl->error.empty()) impl->error = fmt::format("Embree error {}: {}", int(code), str ? str : "");
}

bool has_cutout(const Mesh& mesh) {
  for (const Material& m : mesh.materials)
    if (m.cutout()) return true;
  return false;
}
}  // namespace

UvSets uv_at(const Mesh& mesh, const Triangle& tri, float b1, float b2) {
  UvSets uv = {Vec2f::Zero(), Vec2f::Zero()};
  if (tri.t[0] < 0 || tri.t[1] < 0 || tri.t[2] < 0) return uv;
  const float b0 = 1.0f - b1 - b2;
  uv[0] = b0 * mesh.uvs[tri.t[0]] + b1 * mesh.uvs[tri.t[1]] + b2 * mesh.uvs[tri.t[2]];
  if (!mesh.uvs1.empty()) uv[1] = b0 * mesh.uvs1[tri.t[0]] + b1 * mesh.uvs1[tri.t[1]] + b2 * mesh.uvs1[tri.t[2]];
  return uv;
}

EmbreeScene::EmbreeScene(std::vector<Mesh> meshes) : impl_(std::make_unique<Impl>()), meshes_(std::move(meshes)) {
  // surface() reads three tangents a triangle wherever a mesh has any. Checked before the device
  // exists: the destructor, which releases it, does not run when the constructor throws.
  for (const Mesh& mesh : meshes_)
    if (!mesh.tangents.empty() && mesh.tangents.size() != 3 * mesh.triangles.size())
      throw std::logic_error("EmbreeScene: a mesh's tangents are not three a triangle");
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw std::runtime_error("cannot create the Embree device");
  rtcSetDeviceErrorFunction(impl_->device, embree_error, impl_.get());
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    const Mesh& mesh = meshes_[m];
    RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), mesh.positions.size()));
    if (!vb) throw std::runtime_error(impl_->error.empty() ? "Embree: no vertex buffer" : impl_->error);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
      for (int k = 0; k < 3; ++k) vb[3 * i + k] = mesh.positions[i][k];
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), mesh.triangles.size()));
    if (!ib) throw std::runtime_error(impl_->error.empty() ? "Embree: no index buffer" : impl_->error);
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) ib[3 * i + k] = mesh.triangles[i].v[k];
    if (has_cutout(mesh)) impl_->cutouts = true;
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(impl_->scene, geom, unsigned(m));
    rtcReleaseGeometry(geom);
  }
  if (impl_->cutouts) rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcCommitScene(impl_->scene);
  if (!impl_->error.empty()) throw std::runtime_error(impl_->error);
}

EmbreeScene::~EmbreeScene() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

RTCSceneTy* EmbreeScene::rtc_scene() const { return impl_->scene; }

namespace {
LoggedRay logged(const Ray& ray, float t_near, float t_far, bool shadow) {
  return {
      {ray.origin.x(), ray.origin.y(), ray.origin.z()}, {ray.dir.x(), ray.dir.y(), ray.dir.z()}, t_near, t_far, shadow};
}
}  // namespace

Hit EmbreeScene::intersect(const Ray& ray, float t_near, float t_far) const {
  return nearest(ray, t_near, t_far, CutoutQuery::kStochastic);
}

Hit EmbreeScene::intersect_sheer(const Ray& ray, float t_near, float t_far) const {
  return nearest(ray, t_near, t_far, CutoutQuery::kSheer);
}

Hit EmbreeScene::nearest(const Ray& ray, float t_near, float t_far, CutoutQuery query) const {
  CutoutContext context;
  init_cutout_context(context, meshes_, impl_->cutouts, query);
  RTCRayHit rh;
  rh.ray.org_x = ray.origin.x();
  rh.ray.org_y = ray.origin.y();
  rh.ray.org_z = ray.origin.z();
  rh.ray.dir_x = ray.dir.x();
  rh.ray.dir_y = ray.dir.y();
  rh.ray.dir_z = ray.dir.z();
  rh.ray.tnear = t_near;
  rh.ray.tfar = t_far;
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  if (log_) log_->record(logged(ray, t_near, t_far, false));
  rtcIntersect1(impl_->scene, &context.rtc, &rh);
  Hit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.t = rh.ray.tfar;
  hit.mesh = int(rh.hit.geomID);
  hit.triangle = int(rh.hit.primID);
  hit.b1 = rh.hit.u;
  hit.b2 = rh.hit.v;
  return hit;
}

float EmbreeScene::transmittance(const Ray& ray, float t_near, float t_far) const {
  CutoutContext context;
  init_cutout_context(context, meshes_, impl_->cutouts, CutoutQuery::kShadow);
  RTCRay r;
  r.org_x = ray.origin.x();
  r.org_y = ray.origin.y();
  r.org_z = ray.origin.z();
  r.dir_x = ray.dir.x();
  r.dir_y = ray.dir.y();
  r.dir_z = ray.dir.z();
  r.tnear = t_near;
  r.tfar = t_far;
  r.time = 0.0f;
  r.mask = 0xFFFFFFFFu;
  r.id = 0;
  r.flags = 0;
  if (log_) log_->record(logged(ray, t_near, t_far, true));
  rtcOccluded1(impl_->scene, &context.rtc, &r);
  return r.tfar < 0.0f ? 0.0f : context.transmittance;  // Embree sets tfar to -inf on a hit
}

SurfacePoint EmbreeScene::surface(const Ray& ray, const Hit& hit) const {
  const Mesh& mesh = meshes_[hit.mesh];
  const Triangle& tri = mesh.triangles[hit.triangle];
  const float w0 = 1.0f - hit.b1 - hit.b2, w[3] = {w0, hit.b1, hit.b2};
  const Vec3f& p0 = mesh.positions[tri.v[0]];
  const Vec3f& p1 = mesh.positions[tri.v[1]];
  const Vec3f& p2 = mesh.positions[tri.v[2]];
  SurfacePoint sp;
  // The hit point from barycentrics (more accurate than origin + t·dir far from the origin).
  sp.p_world = w0 * p0 + hit.b1 * p1 + hit.b2 * p2;
  sp.ng_world = (p1 - p0).cross(p2 - p0).normalized();
  sp.material = &mesh.materials[tri.material];
  sp.uv = uv_at(mesh, tri, hit.b1, hit.b2);
  // The interpolated normal, unnormalized (the normal map's n); the geometric one where the mesh
  // has none.
  Vec3f n = sp.ng_world;
  if (tri.n[0] >= 0 && tri.n[1] >= 0 && tri.n[2] >= 0) {
    Vec3f ns = Vec3f::Zero();
    for (int k = 0; k < 3; ++k) ns += w[k] * mesh.normals[tri.n[k]];
    if (ns.squaredNorm() > 0) n = ns;
  }
  sp.ns_world = n.normalized();
  // A tangent-space map's normal (zero without the map or tangents).
  auto mapped_by = [&](const Texture& map) -> Vec3f {
    if (!map || mesh.tangents.empty()) return Vec3f::Zero();
    Vec4f t = Vec4f::Zero();
    for (int k = 0; k < 3; ++k) t += w[k] * mesh.tangents[3 * std::size_t(hit.triangle) + std::size_t(k)];
    return tangent_space_normal(n, t, map.sample(sp.uv));
  };
  Vec3f mapped = mapped_by(sp.material->map_normal), coat_mapped = mapped_by(sp.material->map_clearcoat_normal);
  // The shading normals are brought to the side of the geometric one (winding may differ), then,
  // two-sided, all three face the incoming ray.
  const float to_winding = sp.ns_world.dot(sp.ng_world) < 0 ? -1.0f : 1.0f;
  const float to_ray = sp.ng_world.dot(ray.dir) > 0 ? -1.0f : 1.0f;
  sp.ng_world *= to_ray;
  sp.backfacing = to_ray < 0;
  sp.ns_world *= to_winding * to_ray;
  mapped *= to_winding * to_ray;
  coat_mapped *= to_winding * to_ray;
  sp.n_smooth_world = sp.n_coat_world = sp.ns_world;
  if (mapped.squaredNorm() > 0) {
    mapped = with_strength(sp.ns_world, mapped, sp.material->normal_strength);
    if (mapped.squaredNorm() > 0) sp.ns_world = mapped;
  }
  if (coat_mapped.squaredNorm() > 0) {
    coat_mapped = with_strength(sp.n_smooth_world, coat_mapped, sp.material->clearcoat_normal_strength);
    if (coat_mapped.squaredNorm() > 0) sp.n_coat_world = coat_mapped;
  }
  return sp;
}

}  // namespace insitu
