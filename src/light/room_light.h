// The room as an emitter: with a room box, the box's faces carry the six shots'
// radiance, projected from the capture point c, and are sampled as an area light; its openings
// (windows, open doors) let in distant light, sampled as portals.
//
// Walls. A point q on a wall emits toward the room what the capture point saw in its direction:
// L(q) = cube(ω_c), ω_c = (q − c)/|q − c| (the box projection of real-time engines). Sampling
// draws ω_c from the distribution of the texels c saw on the walls (env_sampling.h, density p_ω
// per steradian at c), follows it to the box at q, and converts to the shading point x:
//   area density on the box   p_A(q) = p_ω(ω_c) · cos θ_c / |q − c|²
//   solid angle at x          p_x(ω) = p_A(q) · |q − x|² / cos θ_x
// with θ_c, θ_x the angles between the face normal at q and the directions to c and to x. The
// radiance found along a direction and the density of drawing it then describe the same emitter,
// so bright texels are drawn where they light x (a cube sampled as seen from c, but looked up
// through the box, gives fireflies: its pdf has nothing to do with what arrives at x).
//
// Openings. Light through an opening is distant: a direction ω from x that leaves the box through
// an opening carries cube(ω), whatever x is (texels across an opening's edge are split between
// the wall and the outside: set_strategies) — the sun through a window falls on the patch of the
// room it reaches, not on every point that sees the window. Where c's own ray along ω met a wall
// (a direction through the opening that the capture point never saw outside: the sky above a
// window, seen from the floor below it), the light is RoomBox::unseen_outside where that is known
// (the photo determines it: relight/unseen_outside.h); else cube(ω), the wall c saw there, a dim
// stand-in for an outside nobody photographed. Two
// portal strategies draw such directions (after Bitterli et al. 2015, "Portal-masked environment
// map sampling", without its rectified parametrisation):
//   directional  ω from the distribution of the texels c saw through the openings, luminance ×
//                solid angle (no MIS compensation: BSDF samples seldom find a window), kept only
//                if ω leaves through an opening from x;  p(ω) = p_out(ω)
//   area         a point uniformly on the openings' area A (an opening chosen by area), ω toward it;
//                p(ω) = |q − x|² / (A · cos θ_x)
// The first finds the sun through the window where it shines; the second the dim sky that the
// first misses where the sun does not reach.
//
// One sample is drawn from the mixture of the three (probabilities p_wall, ½ p_open, ½ p_open with
// p_open = the openings' share of c's irradiance-like power Σ Y·ΔΩ, clamped to [0.2, 0.8]); its
// pdf is the mixture's, so that MIS against the BSDF (and the sample's weight) sees one light. A
// strategy's draw that lands where the strategy has no density (a wall sample in an opening) is
// returned with pdf 0: each strategy's density stays what pdf() says, and the mixture covers
// every direction that carries light.
//
// A point outside the box, and every point without a box, sees the cube as distant light.
#pragma once
#include <functional>
#include <optional>
#include <vector>

#include "light/env_sampling.h"

namespace insitu {

// An axis-aligned rectangle on the wall min[axis] = max[axis] of the box.
struct RoomOpening {
  int axis = 0;
  Vec3f min = Vec3f::Zero(), max = Vec3f::Zero();
};

struct RoomBox {
  Vec3f min = Vec3f::Zero(), max = Vec3f::Zero(), capture = Vec3f::Zero();
  std::vector<RoomOpening> openings;
  // The radiance through the openings along the directions c saw as wall (above); unset: the wall.
  std::optional<Rgb> unseen_outside;
};

// The box's faces, numbered as a cube's: +x, −x, +y, −y, +z, −z (face 2 axis on the max side).
inline int box_face(int axis, bool max_side) { return 2 * axis + (max_side ? 0 : 1); }

// Face `face`'s plane: a point on it (the min corner moved onto it) and its unit normal into the room.
struct FacePlane {
  Vec3f point = Vec3f::Zero(), normal = Vec3f::Zero();
};
FacePlane face_plane(const RoomBox& box, int face);

// The radiance arriving at x along a direction and the density of sample() producing it.
struct RoomLookup {
  Rgb radiance = Rgb::Zero();
  float pdf = 0;  // per steradian at x (the mixture's)
};

struct RoomSample {
  Vec3f dir = Vec3f::Zero();  // unit, from x toward the sampled point
  float distance = 0;         // to the sampled point on the box
  float pdf = 0;              // per steradian at x (the mixture's)
  Rgb radiance = Rgb::Zero();
};

// Visits (face, i, j) of each texel of a cube of n a face whose share (opening_shares(n)) is
// `share`: 0 for the texels c saw wholly on a wall, 1 for those it saw wholly through an opening.
void for_each_texel_of_share(const std::vector<float>& shares, int n, float share,
                             const std::function<void(int, int, int)>& visit);

class RoomLight {
 public:
  // Without a box every call is the distant cube's. `outside_share`: opening_shares(cube.size())
  // of a light of the same box, when many are built (it depends on the box alone); else computed.
  RoomLight(const CubeMap& cube, std::optional<RoomBox> box, const std::vector<float>* outside_share = nullptr);
  RoomLight(const RoomLight&) = delete;  // hundreds of MB at a 1024 face: never copied by accident
  RoomLight& operator=(const RoomLight&) = delete;
  RoomSample sample(const Vec3f& x, float u_pick, float u_s, float u_t) const;
  // radiance(x, dir) and pdf(x, dir) at once, from one exit from the box and one texel lookup:
  // what MIS against a BSDF sample needs.
  RoomLookup lookup(const Vec3f& x, const Vec3f& dir) const;
  float pdf(const Vec3f& x, const Vec3f& dir) const { return lookup(x, dir).pdf; }  // of sample() producing dir at x
  Rgb radiance(const Vec3f& x, const Vec3f& dir) const { return lookup(x, dir).radiance; }  // arriving at x along dir
  // The distance from p to the box along dir, and the axis of the face it leaves through (p inside).
  bool exit(const Vec3f& p, const Vec3f& dir, float* t, int* axis) const;
  // How many openings hold the point q of the box's face across `axis` (0: a wall).
  int openings_at(const Vec3f& q, int axis) const;
  float opening_probability() const { return p_dir_ + p_area_; }
  bool inside(const Vec3f& x) const;  // strictly inside the box (false without one)
  // The share of each texel (face, i, j) of a cube of n a face, indexed (face·n + j)·n + i, whose
  // directions from the capture point leave the box through an opening (empty without openings).
  std::vector<float> opening_shares(int n) const;
  // The cube as seen through the openings from anywhere in the room: the texels c saw wholly on a
  // wall hold RoomBox::unseen_outside where it is known (what lookup() gives through an opening).
  CubeMap seen_through_openings(const CubeMap& cube) const;

 private:
  struct Exit {
    bool valid = false;
    float t = 0;
    int axis = 0, openings = 0;
    Vec3f q = Vec3f::Zero();
  };
  Exit locate(const Vec3f& x, const Vec3f& dir) const;
  RoomLookup lookup(const Vec3f& dir, const Exit& e) const;
  RoomSample along(const Vec3f& dir, const Exit& e) const;
  RoomSample sample_wall(const Vec3f& x, float u, float u_s, float u_t) const;
  RoomSample sample_outside(const Vec3f& x, float u, float u_s, float u_t) const;
  RoomSample sample_portal(const Vec3f& x, float u, float u_s, float u_t) const;
  void set_strategies(const CubeMap& cube, const std::vector<float>* outside_share);

  CubeMap side_of(const CubeMap& cube, const std::vector<float>& outside_share, bool outside) const;
  bool unseen(const Vec3f& dir) const;  // a direction c saw as wall, when the unseen outside is known
  Rgb wall_neighbours(const CubeMap& cube, const std::vector<float>& share, int f, int i, int j) const;

  std::optional<RoomBox> box_;
  // With openings: what c saw on the walls (holding the records; env_sampling.h), the whole cube
  // and what c saw outside (both reading them). Without: the whole cube alone, for distant light
  // and the walls.
  std::optional<EnvSampler> walls_;
  std::optional<EnvSampler> env_;
  std::optional<EnvSampler> outside_;
  std::vector<bool> unseen_;  // per texel, with RoomBox::unseen_outside: c saw it wholly on a wall
  int unseen_face_ = 0;       // its cube's face size
  float p_wall_ = 1, p_dir_ = 0, p_area_ = 0;
  std::vector<float> opening_cdf_;  // by area; opening_cdf_.back() = 1
  float opening_area_ = 0;
};

}  // namespace insitu
