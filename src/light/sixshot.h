// The photo-cube: six plain photos, taken from where the furniture will stand, assembled into a
// radiance cube map (DESIGN.md "Six shots" and "Cube maps").
//
// Each shot is a pinhole photo with square pixels, any size, principal point at its centre and
// horizontal field of view hfov_deg (90° by default), looking nominally along its face's axis:
//   walls (±X, ±Z):   up = +Y
//   ceiling (+Y):     up = −F, so that the bottom edge of the shot points toward F
//   floor (−Y):       up = +F, so that the top edge of the shot points toward F
// where F is the axis of the wall the user faced when shooting ceiling and floor; right =
// forward × up. A shot's aim (ShotSet::aim, from registration: light/shot_registration.h) turns
// those axes to where the shot really looked. Every texel of the cube is the bilinear sample of
// each shot that sees its direction, at the pixel the direction projects to, which mirrors and
// rotates the photos into the cube convention (for a 90° square shot of the face's size the texel
// centres are the pixel centres). Where shots overlap they are feathered (sample_shot in
// sixshot.cpp); one shot alone gives its sample unchanged. Texels that no shot covers (narrow or
// non-square shots) are filled smoothly from their neighbours, across face edges
// (fill_uncovered), and reported as coverage.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "light/cubemap.h"
#include "core/image.h"

namespace insitu {

struct ShotBasis {
  Vec3d forward, up, right;
};
// Camera axes of the shot for `face`, given the faced wall `faced_face` (one of ±X, ±Z).
ShotBasis shot_basis(int face, int faced_face);

// Linear RGB shots indexed by face (+X, −X, +Y, −Y, +Z, −Z).
struct ShotSet {
  std::array<Image, 6> shots;
  std::array<std::string, 6> names;  // for messages
  int faced_face = kNegZ;
  std::array<double, 6> hfov_deg = {90, 90, 90, 90, 90, 90};
  // R_aim per shot: a world rotation from the nominal axes (shot_basis) to the shot's own.
  std::array<Mat3d, 6> aim = {Mat3d::Identity(), Mat3d::Identity(), Mat3d::Identity(),
                              Mat3d::Identity(), Mat3d::Identity(), Mat3d::Identity()};
  void set_hfov(double deg) { hfov_deg.fill(deg); }
};

// Shot s's axes as aimed: aim[s] applied to shot_basis(s, faced_face).
ShotBasis aimed_basis(const ShotSet& set, int s);

struct AssemblyInfo {
  std::array<double, 6> coverage = {1, 1, 1, 1, 1, 1};  // fraction of each face's texels a shot covers
  // Where a face is covered less than fully: per texel, indexed (face·n + j)·n + i, whether a shot
  // covered it (else empty).
  std::vector<bool> covered;
};

// Fills the texels whose weight is 0 smoothly from the others, seamlessly across faces: a
// multiresolution (pull–push) pass over ever coarser cubes, then relaxation toward the solution of
// Laplace's equation at each level on the way back up. `weight` holds 1 where `cube` is known.
void fill_uncovered(CubeMap& cube, const CubeMap& weight);

// The face size that keeps one shot pixel per texel: min over shots of
// width · tan(45°) / tan(hfov/2), capped at max_face_size.
int natural_face_size(const ShotSet& set, int max_face_size = 1024);
// Shot f's own face size at one shot pixel per texel: width · tan(45°) / tan(hfov/2), at least 1.
int shot_face_size(const ShotSet& set, int f);
// A shot wider than a face of n texels needs, shrunk to it (what the assembly samples).
Image shrunk_to_face(const Image& shot, double hfov_deg, int n);

// Assembles the cube; a face the shots cover less than fully is filled (AssemblyInfo::coverage).
// `clipped`, when given, holds each shot's clipped degree (light/hdr_merge.h clipped_mask) in the
// same layout: a clipped pixel yields to a neighbour's that is not, and `clipped_cube` receives the
// masks blended as the radiance is. A texel no shot covers is not clipped (0): its fill is no
// measurement, neither a value nor a lower bound, and inverse lighting scales only light a shot saw
// clip. Throws InputError naming a shot that covers none of the cube.
CubeMap assemble_cube(const ShotSet& set, int face_size, AssemblyInfo* info = nullptr, const ShotSet* clipped = nullptr,
                      CubeMap* clipped_cube = nullptr);

// The reverse, for tests and the demo generator: the shot of `face` a phone would take of a
// radiance function, with `w`×`h` pixels.
// `b`: the shot's axes (shot_basis, or a misaimed shot's).
template <class Radiance>
Image render_shot(const Radiance& radiance, const ShotBasis& b, double hfov_deg, int w, int h) {
  const double f_px = 0.5 * w / std::tan(0.5 * deg_to_rad(hfov_deg));
  Image img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double xc = (x + 0.5 - 0.5 * w) / f_px, yc = -(y + 0.5 - 0.5 * h) / f_px;
      const Vec3d d = (b.forward + xc * b.right + yc * b.up).normalized();
      img.set_rgb(x, y, radiance(d.cast<float>()));
    }
  return img;
}
template <class Radiance>
Image render_shot(const Radiance& radiance, int face, int faced_face, double hfov_deg, int w, int h) {
  return render_shot(radiance, shot_basis(face, faced_face), hfov_deg, w, h);
}

}  // namespace insitu
