#include "scene/catcher_albedo.h"

#include <cmath>
#include <limits>

#include "light/irradiance.h"

namespace insitu {
namespace {

struct FirstHit {
  int surface = -1;  // index into local_scene
  Vec3f normal_world = Vec3f::Zero();
};

// The first local-scene surface along a camera ray: the planes analytically, t = (p − o)·n / (d·n),
// the meshes through Embree. Normals face the ray's origin.
FirstHit first_catcher_hit(const LoadedScene& s, const std::vector<int>& mesh_surface, const Ray& ray) {
  FirstHit best;
  float t_best = std::numeric_limits<float>::infinity();
  for (std::size_t k = 0; k < s.spec.local_scene.size(); ++k) {
    const PlaneSpec& p = s.spec.local_scene[k];
    if (p.mesh) continue;
    const Vec3f n = p.normal.normalized().cast<float>();
    const float dn = ray.dir.dot(n);
    if (std::abs(dn) < 1e-8f) continue;
    const float t = (p.point.cast<float>() - ray.origin).dot(n) / dn;
    if (t > 0 && t < t_best) t_best = t, best = {int(k), dn < 0 ? n : Vec3f(-n)};
  }
  if (s.catcher_meshes && !s.catcher_meshes->empty()) {
    const Hit h = s.catcher_meshes->intersect(ray, 0.0f, t_best);
    if (h.valid()) best = {mesh_surface[std::size_t(h.mesh)], s.catcher_meshes->surface(ray, h).ns_world};
  }
  return best;
}

bool usable(const LoadedScene& s, int x, int y) {
  const float* stored = s.photo.stored.at(x, y);
  const float* lin = s.photo_linear.at(x, y);
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(lin[c])) return false;
    if (s.photo.display_referred && stored[c] >= 0.999f) return false;
  }
  return true;
}

}  // namespace

std::vector<CatcherAlbedo> catcher_albedos(const LoadedScene& s) {
  const auto& planes = s.spec.local_scene;
  std::vector<CatcherAlbedo> out(planes.size());
  std::vector<int> mesh_surface;  // the catcher meshes' order is local_scene's (pipeline.cpp)
  bool estimate = false;
  for (std::size_t k = 0; k < planes.size(); ++k) {
    if (planes[k].mesh) mesh_surface.push_back(int(k));
    if (planes[k].albedo_from_photo)
      estimate = true;
    else
      out[k].albedo = planes[k].albedo;
  }
  if (!estimate) return out;
  const auto field = make_irradiance(IrradianceMode::kExact, s.environment);
  std::vector<Eigen::Array3d> sum(planes.size(), Eigen::Array3d::Zero());
  std::vector<std::size_t> count(planes.size(), 0);
  for (int y = 0; y < s.camera.height; ++y)
    for (int x = 0; x < s.camera.width; ++x) {
      const FirstHit h = first_catcher_hit(s, mesh_surface, s.camera.ray(Vec2d(x + 0.5, y + 0.5)));
      if (h.surface < 0 || !planes[std::size_t(h.surface)].albedo_from_photo || !usable(s, x, y)) continue;
      const Rgb E = field->irradiance(h.normal_world.normalized());
      const float* P = s.photo_linear.at(x, y);
      for (int c = 0; c < 3; ++c) sum[std::size_t(h.surface)][c] += kPi * double(P[c]) / std::max(1e-30, double(E[c]));
      ++count[std::size_t(h.surface)];
    }
  for (std::size_t k = 0; k < planes.size(); ++k) {
    if (!planes[k].albedo_from_photo || count[k] == 0) continue;
    out[k].albedo = (sum[k] / double(count[k])).min(0.95).max(0.0).cast<float>();
    out[k].pixels = count[k];
    out[k].from_photo = true;
  }
  return out;
}

}  // namespace insitu
