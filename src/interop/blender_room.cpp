// The room box's walls for the Blender export (interop/blender_export.h): each wall cut into cells
// along its openings' edges, the cells inside an opening dropped.
#include <algorithm>
#include <cmath>

#include "interop/blender_export.h"

namespace insitu {
namespace {

using Opening = EnvironmentSpec::Opening;

// The infinite local-scene plane the wall {p : p[axis] = w} lies on, if any.
bool on_local_plane(int axis, double w, double size_m, const std::vector<PlaneSpec>& local_scene) {
  for (const PlaneSpec& p : local_scene) {
    if (p.mesh) continue;
    const Vec3d n = p.normal.normalized();
    if (std::abs(std::abs(n[axis]) - 1.0) < 1e-9 && std::abs(p.point[axis] - w) <= 1e-6 * size_m) return true;
  }
  return false;
}

bool inside(const Opening& o, int u, int v, double cu, double cv) {
  return cu > o.min[u] && cu < o.max[u] && cv > o.min[v] && cv < o.max[v];
}

std::vector<double> cuts(double lo, double hi, const std::vector<const Opening*>& openings, int axis) {
  std::vector<double> c = {lo, hi};
  for (const Opening* o : openings)
    for (double x : {o->min[axis], o->max[axis]}) c.push_back(std::clamp(x, lo, hi));
  std::sort(c.begin(), c.end());
  c.erase(std::unique(c.begin(), c.end()), c.end());
  return c;
}

// One wall: axis a, at min (inward +e_a) or max (inward −e_a). With u = a+1, v = a+2 (cyclic),
// e_u × e_v = e_a, so (u0,v0), (u1,v0), (u1,v1), (u0,v1) is counter-clockwise seen from +e_a.
void add_wall(const EnvironmentSpec::RoomBox& box, int a, bool at_min, std::vector<Quad>& out) {
  const double w = at_min ? box.min[a] : box.max[a];
  const int u = (a + 1) % 3, v = (a + 2) % 3;
  const double size_m = (box.max - box.min).norm();
  std::vector<const Opening*> openings;
  for (const Opening& o : box.openings)
    if (o.axis == a && std::abs(o.min[a] - w) <= 1e-9 * std::max(1.0, size_m)) openings.push_back(&o);
  const std::vector<double> us = cuts(box.min[u], box.max[u], openings, u),
                            vs = cuts(box.min[v], box.max[v], openings, v);
  for (std::size_t i = 0; i + 1 < us.size(); ++i)
    for (std::size_t j = 0; j + 1 < vs.size(); ++j) {
      const double cu = 0.5 * (us[i] + us[i + 1]), cv = 0.5 * (vs[j] + vs[j + 1]);
      if (std::any_of(openings.begin(), openings.end(), [&](const Opening* o) { return inside(*o, u, v, cu, cv); }))
        continue;
      auto corner = [&](double pu, double pv) {
        Vec3d p;
        p[a] = w, p[u] = pu, p[v] = pv;
        return p;
      };
      Quad q = {corner(us[i], vs[j]), corner(us[i + 1], vs[j]), corner(us[i + 1], vs[j + 1]), corner(us[i], vs[j + 1])};
      if (!at_min) std::reverse(q.begin(), q.end());
      out.push_back(q);
    }
}

}  // namespace

std::vector<Quad> room_wall_quads(const EnvironmentSpec::RoomBox& box, const std::vector<PlaneSpec>& local_scene) {
  std::vector<Quad> out;
  const double size_m = (box.max - box.min).norm();
  for (int a = 0; a < 3; ++a)
    for (bool at_min : {true, false})
      if (!on_local_plane(a, at_min ? box.min[a] : box.max[a], size_m, local_scene)) add_wall(box, a, at_min, out);
  return out;
}

}  // namespace insitu
