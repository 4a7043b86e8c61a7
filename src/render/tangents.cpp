#include "render/tangents.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <tuple>
#include <unordered_map>

namespace insitu {
namespace {

struct Corner {
  Vec3f p, n;
  Vec2f uv;
};

Corner corner_of(const Mesh& mesh, const Triangle& tri, int k, int uv_set) {
  const std::vector<Vec2f>& uvs = uv_set == 0 ? mesh.uvs : mesh.uvs1;
  Corner c;
  c.p = mesh.positions[tri.v[std::size_t(k)]];
  if (tri.n[std::size_t(k)] >= 0) {
    c.n = mesh.normals[std::size_t(tri.n[std::size_t(k)])];
  } else {
    const Vec3f& p0 = mesh.positions[tri.v[0]];
    c.n = (mesh.positions[tri.v[1]] - p0).cross(mesh.positions[tri.v[2]] - p0).normalized();
  }
  const std::int32_t t = tri.t[std::size_t(k)];
  c.uv = t >= 0 && std::size_t(t) < uvs.size() ? uvs[std::size_t(t)] : Vec2f::Zero();
  return c;
}

// Corners welded where position, normal and UV are equal (−0 and +0 alike): one id per corner.
std::vector<int> weld(const std::vector<Corner>& corners) {
  using Key = std::array<std::uint32_t, 8>;
  struct Hash {
    std::size_t operator()(const Key& k) const {
      std::size_t h = 1469598103934665603ull;
      for (std::uint32_t x : k) h = (h ^ x) * 1099511628211ull;
      return h;
    }
  };
  std::unordered_map<Key, int, Hash> ids;
  std::vector<int> id(corners.size());
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Corner& c = corners[i];
    const float f[8] = {c.p.x(), c.p.y(), c.p.z(), c.n.x(), c.n.y(), c.n.z(), c.uv.x(), c.uv.y()};
    Key k;
    for (int j = 0; j < 8; ++j) {
      const float x = f[j] + 0.0f;  // −0 → +0
      std::memcpy(&k[std::size_t(j)], &x, 4);
    }
    id[i] = ids.emplace(k, int(ids.size())).first->second;
  }
  return id;
}

Vec3f normalized_if_nonzero(const Vec3f& v) { return v.squaredNorm() > 0 ? Vec3f(v.normalized()) : v; }
Vec3f projected(const Vec3f& v, const Vec3f& n) { return normalized_if_nonzero(v - n.dot(v) * n); }

struct TriInfo {
  Vec3f os = Vec3f::Zero();                  // ∂p/∂u's direction
  bool orient = false;                       // orientation preserving: UV area > 0
  bool any = true;                           // groups with any: no usable ∂p/∂u
  std::array<int, 3> neighbour{-1, -1, -1};  // across edge i (corner i to i + 1)
  std::array<int, 3> group{-1, -1, -1};      // of corner i
};

// Mikkelsen's eqs. 18–19: ∂p/∂u ∝ t31y · d1 − t21y · d2, signed by the UV area.
TriInfo triangle_info(const Corner* c) {
  TriInfo t;
  const Vec2f t21 = c[1].uv - c[0].uv, t31 = c[2].uv - c[0].uv;
  const Vec3f d1 = c[1].p - c[0].p, d2 = c[2].p - c[0].p;
  const float area2 = t21.x() * t31.y() - t21.y() * t31.x();
  const Vec3f os = t31.y() * d1 - t21.y() * d2, ot = -t31.x() * d1 + t21.x() * d2;
  t.orient = area2 > 0;
  if (std::abs(area2) > std::numeric_limits<float>::min()) {
    const float s = t.orient ? 1.0f : -1.0f, len_s = os.norm(), len_t = ot.norm();
    if (len_s > std::numeric_limits<float>::min()) t.os = os * (s / len_s);
    const float min = std::numeric_limits<float>::min();
    t.any = !(len_s / std::abs(area2) > min && len_t / std::abs(area2) > min);
  }
  return t;
}

class Mikk {
 public:
  Mikk(std::vector<Corner> corners, std::vector<int> good)
      : c_(std::move(corners)), id_(weld(c_)), good_(std::move(good)), info_(good_.size()) {
    for (std::size_t g = 0; g < good_.size(); ++g) info_[g] = triangle_info(&c_[3 * std::size_t(good_[g])]);
    build_neighbours();
    build_groups();
  }

  // The space of corner k of good triangle g.
  Vec4f space(std::size_t g, int k) const {
    const int group = info_[g].group[std::size_t(k)];
    if (group < 0) return Vec4f(1, 0, 0, -1);  // mikktspace.c's default space (bOrient false)
    const Vec3f t = groups_[std::size_t(group)].tangent;
    return Vec4f(t.x(), t.y(), t.z(), groups_[std::size_t(group)].orient ? 1.0f : -1.0f);
  }
  int welded(std::size_t g, int k) const { return id_[3 * std::size_t(good_[g]) + std::size_t(k)]; }
  int welded_corner(std::size_t corner) const { return id_[corner]; }

 private:
  struct Group {
    int vertex;  // welded id
    bool orient;
    std::vector<int> members;  // good triangles
    Vec3f tangent = Vec3f::Zero();
  };

  // Edges paired with the first unpaired, oppositely directed edge of a later triangle, in the order
  // of (smaller id, larger id, triangle): mikktspace.c's BuildNeighborsFast.
  void build_neighbours() {
    struct Edge {
      int lo, hi, tri, k;
    };
    std::vector<Edge> edges;
    for (std::size_t g = 0; g < good_.size(); ++g)
      for (int k = 0; k < 3; ++k) {
        const int a = welded(g, k), b = welded(g, (k + 1) % 3);
        edges.push_back({std::min(a, b), std::max(a, b), int(g), k});
      }
    std::sort(edges.begin(), edges.end(),
              [](const Edge& x, const Edge& y) { return std::tie(x.lo, x.hi, x.tri) < std::tie(y.lo, y.hi, y.tri); });
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const Edge& e = edges[i];
      if (info_[std::size_t(e.tri)].neighbour[std::size_t(e.k)] >= 0) continue;
      const int from = welded(std::size_t(e.tri), e.k);
      for (std::size_t j = i + 1; j < edges.size() && edges[j].lo == e.lo && edges[j].hi == e.hi; ++j) {
        const Edge& f = edges[j];
        if (welded(std::size_t(f.tri), (f.k + 1) % 3) != from) continue;  // same direction
        if (info_[std::size_t(f.tri)].neighbour[std::size_t(f.k)] >= 0) continue;
        info_[std::size_t(e.tri)].neighbour[std::size_t(e.k)] = f.tri;
        info_[std::size_t(f.tri)].neighbour[std::size_t(f.k)] = e.tri;
        break;
      }
    }
  }

  // mikktspace.c's Build4RuleGroups and AssignRecur, with the recursion on an explicit stack
  // (left neighbour's subtree first, as the recursion visits it).
  void build_groups() {
    for (std::size_t g = 0; g < good_.size(); ++g)
      for (int k = 0; k < 3; ++k) {
        if (info_[g].any || info_[g].group[std::size_t(k)] >= 0) continue;
        groups_.push_back({welded(g, k), info_[g].orient, {int(g)}});
        const int group = int(groups_.size() - 1);
        info_[g].group[std::size_t(k)] = group;
        std::vector<int> stack = {info_[g].neighbour[std::size_t((k + 2) % 3)], info_[g].neighbour[std::size_t(k)]};
        while (!stack.empty()) {
          const int t = stack.back();
          stack.pop_back();
          if (t >= 0) join(std::size_t(t), group, stack);
        }
        evaluate(groups_[std::size_t(group)]);
      }
  }

  void join(std::size_t t, int group, std::vector<int>& stack) {
    Group& gr = groups_[std::size_t(group)];
    TriInfo& ti = info_[t];
    int k = 0;
    while (k < 3 && welded(t, k) != gr.vertex) ++k;
    if (k == 3 || ti.group[std::size_t(k)] >= 0) return;
    // The first group to reach a group-with-any triangle sets its orientation.
    if (ti.any && ti.group == std::array<int, 3>{-1, -1, -1}) ti.orient = gr.orient;
    if (ti.orient != gr.orient) return;
    gr.members.push_back(int(t));
    ti.group[std::size_t(k)] = group;
    stack.push_back(ti.neighbour[std::size_t((k + 2) % 3)]);
    stack.push_back(ti.neighbour[std::size_t(k)]);
  }

  // mikktspace.c's EvalTspace: the angle-weighted sum of the members' projected tangents.
  void evaluate(Group& gr) const {
    Vec3f sum = Vec3f::Zero();
    for (int m : gr.members) {
      const TriInfo& ti = info_[std::size_t(m)];
      if (ti.any) continue;
      int k = 0;
      while (welded(std::size_t(m), k) != gr.vertex) ++k;
      const Corner* c = &c_[3 * std::size_t(good_[std::size_t(m)])];
      const Vec3f& n = c[k].n;
      const Vec3f v1 = projected(c[(k + 2) % 3].p - c[k].p, n), v2 = projected(c[(k + 1) % 3].p - c[k].p, n);
      const float angle = std::acos(std::clamp(v1.dot(v2), -1.0f, 1.0f));
      sum += angle * projected(ti.os, n);
    }
    gr.tangent = normalized_if_nonzero(sum);
  }

  std::vector<Corner> c_;
  std::vector<int> id_;
  std::vector<int> good_;  // the triangles without two equal positions, in mesh order
  std::vector<TriInfo> info_;
  std::vector<Group> groups_;
};

}  // namespace

std::vector<Vec4f> mikktspace_tangents(const Mesh& mesh, int uv_set) {
  const std::size_t n = mesh.triangles.size();
  std::vector<Corner> corners(3 * n);
  std::vector<int> good, degenerate;
  for (std::size_t f = 0; f < n; ++f) {
    for (int k = 0; k < 3; ++k) corners[3 * f + std::size_t(k)] = corner_of(mesh, mesh.triangles[f], k, uv_set);
    const Vec3f &a = corners[3 * f].p, &b = corners[3 * f + 1].p, &c = corners[3 * f + 2].p;
    (a == b || a == c || b == c ? degenerate : good).push_back(int(f));
  }
  const Mikk mikk(std::move(corners), good);
  std::vector<Vec4f> out(3 * n, Vec4f(1, 0, 0, -1));
  std::unordered_map<int, Vec4f> first_space;  // per welded id, its first good corner's space
  for (std::size_t g = 0; g < good.size(); ++g)
    for (int k = 0; k < 3; ++k) {
      const Vec4f s = mikk.space(g, k);
      out[3 * std::size_t(good[g]) + std::size_t(k)] = s;
      first_space.emplace(mikk.welded(g, k), s);
    }
  // mikktspace.c's DegenEpilogue: a degenerate triangle's corner copies a good one's.
  for (int f : degenerate)
    for (std::size_t k = 0; k < 3; ++k)
      if (auto it = first_space.find(mikk.welded_corner(3 * std::size_t(f) + k)); it != first_space.end())
        out[3 * std::size_t(f) + k] = it->second;
  return out;
}

}  // namespace insitu
