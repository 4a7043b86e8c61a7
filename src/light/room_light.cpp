#include "light/room_light.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <tbb/parallel_for.h>

#include "core/colour.h"
#include "light/texel_geometry.h"

namespace insitu {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// The two axes of a face across `axis`.
int other_axis(int axis, int k) { return (axis + 1 + k) % 3; }

float rect_area(const RoomOpening& o) {
  return (o.max[other_axis(o.axis, 0)] - o.min[other_axis(o.axis, 0)]) *
         (o.max[other_axis(o.axis, 1)] - o.min[other_axis(o.axis, 1)]);
}

}  // namespace

FacePlane face_plane(const RoomBox& box, int face) {
  const int axis = face / 2;
  const bool max_side = face % 2 == 0;
  FacePlane f;
  f.point = box.min;
  if (max_side) f.point[axis] = box.max[axis];
  f.normal[axis] = max_side ? -1.0f : 1.0f;
  return f;
}

RoomLight::RoomLight(const CubeMap& cube, std::optional<RoomBox> box, const std::vector<float>* outside_share)
    : box_(std::move(box)) {
  if (box_ && !box_->openings.empty())
    set_strategies(cube, outside_share);
  else
    env_.emplace(cube);
}

// From 4 × 4 directions per texel: a sun texel across the window's edge belongs to both parts.
std::vector<float> RoomLight::opening_shares(int n) const {
  if (!box_ || box_->openings.empty()) return {};
  const int m = 4;
  std::vector<float> share(std::size_t(6) * n * n);
  // 16 rays a texel, 100 million at a 1024 face: the face rows in parallel.
  tbb::parallel_for(0, 6 * n, [&](int row) {
    const int f = row / n, j = row % n;
    for (int i = 0; i < n; ++i) {
      int through = 0;
      for (int b = 0; b < m; ++b)
        for (int a = 0; a < m; ++a) {
          const float s = (float(i) + (float(a) + 0.5f) / m) / float(n),
                      t = (float(j) + (float(b) + 0.5f) / m) / float(n);
          const Vec3f d = face_to_direction(f, s, t).normalized();
          float t_exit = 0;
          int axis = 0;
          through += exit(box_->capture, d, &t_exit, &axis) && openings_at(box_->capture + t_exit * d, axis) > 0;
        }
      share[(std::size_t(f) * n + j) * n + i] = float(through) / float(m * m);
    }
  });
  return share;
}

// The wall's radiance in a texel across an opening's edge: the mean of the texels within two of it
// on its face that c saw wholly on a wall (the texel's own value where there is none).
Rgb RoomLight::wall_neighbours(const CubeMap& cube, const std::vector<float>& share, int f, int i, int j) const {
  const int n = cube.size();
  Rgb sum = Rgb::Zero();
  int count = 0;
  for (int b = std::max(0, j - 2); b <= std::min(n - 1, j + 2); ++b)
    for (int a = std::max(0, i - 2); a <= std::min(n - 1, i + 2); ++a)
      if (share[(std::size_t(f) * n + b) * n + a] == 0.0f) sum += cube.texel(f, a, b), ++count;
  return count > 0 ? Rgb(sum / float(count)) : cube.texel(f, i, j);
}

// With openings: the cube split into what c saw of the walls and of the outside. A texel wholly on
// one side is that side's (and the other's fallback). A texel across an opening's edge, of share
// s outside, mixes L = (1 − s) L_wall + s L_out: L_wall is taken from its wall neighbours, so that
// the sun in a texel at a window's edge lights the room through the window, not as a glowing strip
// of wall beside it. What c saw outside, s·L_out = L − (1 − s) L_wall ≥ 0, is taken as all the
// outside light in the texel (its radiance over the whole texel): a point that sees the whole
// texel through the window then receives the sun's energy that c saw, not 1/s times it, which
// a sun at the window's edge would give if L_out filled the texel. (For an even sky it
// underestimates the thin ring of texels along the window's edge by s.) Each side is sampled in
// proportion to its light and its share of the texel.
// One side of the split: the wall's (outside = false) or the outside's radiance in every texel.
CubeMap RoomLight::side_of(const CubeMap& cube, const std::vector<float>& outside_share, bool outside) const {
  const int n = cube.size();
  CubeMap side = cube;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const float s_out = outside_share[(std::size_t(f) * n + j) * n + i];
        if (s_out == 0.0f || s_out == 1.0f) continue;
        const Rgb wall = wall_neighbours(cube, outside_share, f, i, j);
        side.set_texel(f, i, j, outside ? Rgb((cube.texel(f, i, j) - (1 - s_out) * wall).max(0.0f)) : wall);
      }
  side.update_borders();
  return side;
}

namespace {

// Σ share·Y·ΔΩ over the texels: a side's irradiance-like power as c saw it.
double side_power(const CubeMap& side, const std::function<double(int, int, int)>& share) {
  const int n = side.size();
  const std::vector<double> face_omega = face_solid_angles(n);
  double power = 0;
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        power += share(f, i, j) * face_omega[std::size_t(j) * std::size_t(n) + std::size_t(i)] *
                 std::max(0.0f, luminance(side.texel(f, i, j)));
  return power;
}

}  // namespace

void RoomLight::set_strategies(const CubeMap& cube, const std::vector<float>* given_share) {
  const int n = cube.size();
  const std::size_t texels = std::size_t(6) * std::size_t(n) * std::size_t(n);
  const std::vector<float> own_share =
      given_share && given_share->size() == texels ? std::vector<float>{} : opening_shares(n);
  const std::vector<float>& outside_share = own_share.empty() ? *given_share : own_share;
  auto share_of = [&](int f, int i, int j) { return double(outside_share[(std::size_t(f) * n + j) * n + i]); };
  auto wall_share = [&](int f, int i, int j) { return 1.0 - share_of(f, i, j); };
  // Each side's cube lives only while its sampler is built (at a 1024 face a cube is 76 MB). The
  // walls' sampler holds the records, radiance beside P_i (a wall's pdf and radiance, the queries
  // most paths in a room make, in one cache line); the whole cube's and the outside's read them,
  // keeping aside only the texels across an opening's edge, where their radiance differs.
  double power_wall = 0, power_out = 0;
  {
    const CubeMap wall_cube = side_of(cube, outside_share, false);
    power_wall = side_power(wall_cube, wall_share);
    walls_.emplace(wall_cube, wall_share);
  }
  env_.emplace(cube, *walls_, EnvSampler::TexelShare{});
  {
    const CubeMap outside_cube = side_of(cube, outside_share, true);
    power_out = side_power(outside_cube, share_of);
    outside_.emplace(outside_cube, *walls_, share_of, /*mis_compensation=*/false);
  }
  // The texels c saw wholly on a wall, whose radiance through an opening is the unseen outside's
  // (lookup): their density is the outside strategy's floor whatever their radiance, so it is
  // given there, a bit a texel, not kept in a cube of its own.
  if (box_->unseen_outside) {
    unseen_.resize(texels);
    unseen_face_ = n;
    for (std::size_t k = 0; k < texels; ++k) unseen_[k] = outside_share[k] == 0.0f;
  }
  const double share = power_out + power_wall > 0 ? power_out / (power_out + power_wall) : 0.5;
  const float p_open = float(std::clamp(share, 0.2, 0.8));
  p_wall_ = 1 - p_open;
  p_dir_ = p_area_ = 0.5f * p_open;
  for (const RoomOpening& o : box_->openings) opening_cdf_.push_back(opening_area_ += rect_area(o));
  for (float& c : opening_cdf_) c /= opening_area_;
  opening_cdf_.back() = 1.0f;
}

void for_each_texel_of_share(const std::vector<float>& shares, int n, float share,
                             const std::function<void(int, int, int)>& visit) {
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (shares[texel_index(f, i, j, n)] == share) visit(f, i, j);
}

CubeMap RoomLight::seen_through_openings(const CubeMap& cube) const {
  CubeMap out = cube;
  if (!box_ || !box_->unseen_outside) return out;
  const Rgb fill = *box_->unseen_outside;
  for_each_texel_of_share(opening_shares(cube.size()), cube.size(), 0.0f,
                          [&](int f, int i, int j) { out.set_texel(f, i, j, fill); });
  out.update_borders();
  return out;
}

bool RoomLight::unseen(const Vec3f& dir) const {
  if (unseen_.empty()) return false;
  const int n = unseen_face_;
  const FaceCoord fc = direction_to_face(dir);
  const int i = nearest_texel_index(fc.s, n), j = nearest_texel_index(fc.t, n);
  return unseen_[texel_index(fc.face, i, j, n)];
}

bool RoomLight::inside(const Vec3f& x) const {
  return box_ && (x.array() > box_->min.array()).all() && (x.array() < box_->max.array()).all();
}

bool RoomLight::exit(const Vec3f& p, const Vec3f& dir, float* t, int* axis) const {
  float t_exit = kInfinity;
  int a = -1;
  for (int k = 0; k < 3; ++k) {
    if (dir[k] == 0) continue;
    const float tk = ((dir[k] > 0 ? box_->max[k] : box_->min[k]) - p[k]) / dir[k];
    if (tk < t_exit) t_exit = tk, a = k;
  }
  if (a < 0 || !(t_exit > 0) || !std::isfinite(t_exit)) return false;
  *t = t_exit;
  *axis = a;
  return true;
}

int RoomLight::openings_at(const Vec3f& q, int axis) const {
  int count = 0;
  for (const RoomOpening& o : box_->openings) {
    if (o.axis != axis || std::abs(q[axis] - o.min[axis]) > 1e-4f * (box_->max - box_->min).maxCoeff()) continue;
    const int a = other_axis(axis, 0), b = other_axis(axis, 1);
    count += q[a] >= o.min[a] && q[a] <= o.max[a] && q[b] >= o.min[b] && q[b] <= o.max[b];
  }
  return count;
}

RoomLight::Exit RoomLight::locate(const Vec3f& x, const Vec3f& dir) const {
  Exit e;
  if (!exit(x, dir, &e.t, &e.axis)) return e;
  e.valid = true;
  e.q = x + e.t * dir;
  e.q[e.axis] = dir[e.axis] > 0 ? box_->max[e.axis] : box_->min[e.axis];
  e.openings = openings_at(e.q, e.axis);
  return e;
}

// Along dir, leaving the box at e: through an opening the light is distant (the cube by
// direction), with the portal strategies' density; a wall shows what c saw of it, with the wall
// strategy's density converted to x (the header's p_x(ω)).
RoomLookup RoomLight::lookup(const Vec3f& dir, const Exit& e) const {
  if (!e.valid) return {env_->radiance(dir), 0.0f};
  const float cos_x = std::abs(dir[e.axis]);
  if (e.openings > 0) {
    if (!outside_) return {env_->radiance(dir), 0.0f};
    const EnvLookup l = outside_->lookup(dir);
    const Rgb radiance = unseen(dir) ? *box_->unseen_outside : l.radiance;
    if (!(cos_x > 0)) return {radiance, 0.0f};
    return {radiance, p_dir_ * l.pdf + p_area_ * float(e.openings) * e.t * e.t / (opening_area_ * cos_x)};
  }
  const EnvSampler& walls = walls_ ? *walls_ : *env_;
  const Vec3f v = e.q - box_->capture;
  const float t_c = v.norm();
  if (!(t_c > 0)) return {walls.radiance(dir), 0.0f};
  const Vec3f w_c = v / t_c;
  const EnvLookup l = walls.lookup(w_c);
  if (!(cos_x > 0)) return {l.radiance, 0.0f};
  // cos θ_c = |ω_c[axis]|: the face's normal is that axis.
  const float cos_c = std::abs(w_c[e.axis]);
  return {l.radiance, p_wall_ * l.pdf * cos_c / (t_c * t_c) * (e.t * e.t) / cos_x};
}

RoomLookup RoomLight::lookup(const Vec3f& x, const Vec3f& dir) const {
  if (inside(x)) return lookup(dir, locate(x, dir));
  const EnvLookup l = env_->lookup(dir);
  return {l.radiance, l.pdf};
}

// The sample along dir, which leaves the box at e: the mixture's pdf and the radiance there, as
// lookup() gives them.
RoomSample RoomLight::along(const Vec3f& dir, const Exit& e) const {
  RoomSample s;
  if (!e.valid) return s;
  const RoomLookup l = lookup(dir, e);
  s.radiance = l.radiance;
  s.pdf = s.radiance.allFinite() ? l.pdf : 0.0f;
  s.dir = dir;
  s.distance = e.t;
  return s;
}

RoomSample RoomLight::sample_wall(const Vec3f& x, float u, float u_s, float u_t) const {
  const EnvSample es = (walls_ ? *walls_ : *env_).sample(u, u_s, u_t);
  float t_c = 0;
  int axis = 0;
  if (!exit(box_->capture, es.dir, &t_c, &axis)) return {};
  const Vec3f d = box_->capture + t_c * es.dir - x;
  const float dist = d.norm();
  if (!(dist > 0)) return {};
  const Exit e = locate(x, d / dist);
  return e.openings == 0 ? along(d / dist, e) : RoomSample{};  // an opening: the portals' part
}

RoomSample RoomLight::sample_outside(const Vec3f& x, float u, float u_s, float u_t) const {
  const EnvSample es = outside_->sample(u, u_s, u_t);
  const Exit e = locate(x, es.dir);
  return e.openings > 0 ? along(es.dir, e) : RoomSample{};
}

RoomSample RoomLight::sample_portal(const Vec3f& x, float u, float u_s, float u_t) const {
  const std::size_t k =
      std::size_t(std::lower_bound(opening_cdf_.begin(), opening_cdf_.end(), u) - opening_cdf_.begin());
  const RoomOpening& o = box_->openings[std::min(k, box_->openings.size() - 1)];
  Vec3f q = o.min;
  const int a = other_axis(o.axis, 0), b = other_axis(o.axis, 1);
  q[a] += u_s * (o.max[a] - o.min[a]);
  q[b] += u_t * (o.max[b] - o.min[b]);
  const Vec3f d = q - x;
  const float dist = d.norm();
  if (!(dist > 0)) return {};
  const Exit e = locate(x, d / dist);
  return e.openings > 0 ? along(d / dist, e) : RoomSample{};
}

RoomSample RoomLight::sample(const Vec3f& x, float u_pick, float u_s, float u_t) const {
  if (!inside(x)) {
    const EnvSample es = env_->sample(u_pick, u_s, u_t);
    return {es.dir, kInfinity, es.pdf, env_->radiance(es.dir)};
  }
  // One of the strategies, chosen by u_pick, which is then stretched back onto [0, 1).
  auto stretch = [](float u, float lo, float p) { return std::min((u - lo) / p, std::nextafter(1.0f, 0.0f)); };
  if (u_pick < p_wall_) return sample_wall(x, stretch(u_pick, 0, p_wall_), u_s, u_t);
  if (u_pick < p_wall_ + p_dir_) return sample_outside(x, stretch(u_pick, p_wall_, p_dir_), u_s, u_t);
  return sample_portal(x, stretch(u_pick, p_wall_ + p_dir_, p_area_), u_s, u_t);
}

}  // namespace insitu
