#include "render/embree_scene.h"

#include <embree3/rtcore.h>

#include <stdexcept>
#include <string>
#include <fmt/format.h>

#include "render/ray_log.h"

namespace insitu {

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::string error;  // the first error Embree reported, if any
};

namespace {
// Embree reports programming errors and out-of-memory here: the first is kept, and building the
// scene then fails with it (an internal error, exit code 1), instead of rendering from a scene
// that is not what was asked for.
void embree_error(void* user, RTCError code, const char* str) {
  auto* impl = static_cast<EmbreeScene::Impl*>(user);
  if (impl->error.empty()) impl->error = fmt::format("Embree error {}: {}", int(code), str ? str : "");
}
}  // namespace

EmbreeScene::EmbreeScene(std::vector<Mesh> meshes) : impl_(std::make_unique<Impl>()), meshes_(std::move(meshes)) {
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
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(impl_->scene, geom, unsigned(m));
    rtcReleaseGeometry(geom);
  }
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
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
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
  rtcIntersect1(impl_->scene, &context, &rh);
  Hit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.t = rh.ray.tfar;
  hit.mesh = int(rh.hit.geomID);
  hit.triangle = int(rh.hit.primID);
  hit.b1 = rh.hit.u;
  hit.b2 = rh.hit.v;
  return hit;
}

bool EmbreeScene::occluded(const Ray& ray, float t_near, float t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
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
  rtcOccluded1(impl_->scene, &context, &r);
  return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
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
  sp.ns_world = sp.ng_world;
  if (tri.n[0] >= 0 && tri.n[1] >= 0 && tri.n[2] >= 0) {
    Vec3f ns = Vec3f::Zero();
    for (int k = 0; k < 3; ++k) ns += w[k] * mesh.normals[tri.n[k]];
    if (ns.squaredNorm() > 0) {
      ns.normalize();
      // The interpolated normal is brought to the side of the geometric one (winding may differ).
      sp.ns_world = ns.dot(sp.ng_world) < 0 ? Vec3f(-ns) : ns;
    }
  }
  if (tri.t[0] >= 0 && tri.t[1] >= 0 && tri.t[2] >= 0) {
    sp.uv[0] = w0 * mesh.uvs[tri.t[0]] + hit.b1 * mesh.uvs[tri.t[1]] + hit.b2 * mesh.uvs[tri.t[2]];
    if (!mesh.uvs1.empty())
      sp.uv[1] = w0 * mesh.uvs1[tri.t[0]] + hit.b1 * mesh.uvs1[tri.t[1]] + hit.b2 * mesh.uvs1[tri.t[2]];
  }
  // Two-sided: both normals face the incoming ray.
  if (sp.ng_world.dot(ray.dir) > 0) {
    sp.ng_world = -sp.ng_world;
    sp.ns_world = -sp.ns_world;
  }
  sp.material = &mesh.materials[tri.material];
  return sp;
}

}  // namespace insitu
