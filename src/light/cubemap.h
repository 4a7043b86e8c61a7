// Cube maps in the OpenGL face convention (DESIGN.md "Cube maps").
//
// Faces +X, −X, +Y, −Y, +Z, −Z. For a direction r with major-axis component ma:
//   face  sc   tc          s = (sc/|ma| + 1)/2,  t = (tc/|ma| + 1)/2
//   +X   −rz  −ry          s grows with the column, t with the row (row 0 is t = 0).
//   −X   +rz  −ry
//   +Y   +rx  +rz
//   −Y   +rx  −rz
//   +Z   +rx  −ry
//   −Z   −rx  −ry
//
// Each face is stored with a one-texel border copied from its neighbours, so a bilinear lookup
// is seamless across face edges: exactly on an edge both faces return the mean of their two
// edge texels, and at a corner all three return the mean of their corner texels.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>

#include "core/image.h"
#include "core/math.h"

namespace insitu {

enum CubeFace : int { kPosX = 0, kNegX, kPosY, kNegY, kPosZ, kNegZ };
const char* face_name(int face);  // "+x", "-x", "up", "down", "+z", "-z": the scene file's keys

struct FaceCoord {
  int face;
  float s, t;  // in [0,1]
};

// The texel holding face coordinate s ∈ [0, 1] on a face of n texels: floor(s·n), with s = 1 in
// the last texel. The one nearest-texel rule (CubeMap::lookup_nearest, the environment sampler).
inline int nearest_texel_index(float s, int n) { return std::clamp(int(std::floor(s * float(n))), 0, n - 1); }

// A texel's index in a per-texel array over the six faces of n² texels: (face·n + j)·n + i.
inline std::size_t texel_index(int face, int i, int j, int n) {
  return (std::size_t(face) * std::size_t(n) + std::size_t(j)) * std::size_t(n) + std::size_t(i);
}

// Direction (any length, non-zero) -> face and (s, t) by the table above.
FaceCoord direction_to_face(const Vec3f& dir);
// (s, t) of `dir` on the plane of a given face (outside [0,1] when dir is not on that face).
FaceCoord project_to_face(int face, const Vec3f& dir);
// The inverse: a point (s, t) of a face (s, t may leave [0,1] onto the face's plane) -> the
// unnormalized direction through it.
Vec3f face_to_direction(int face, float s, float t);
// The unit direction through the centre of texel (i, j) of a face of size n.
Vec3f texel_direction(int face, int i, int j, int n);

class CubeMap {
 public:
  CubeMap() = default;
  explicit CubeMap(int size);  // black

  int size() const { return size_; }
  // Texel (i, j) of a face: i the column, j the row; -1 and size() address the border.
  Rgb texel(int face, int i, int j) const;
  void set_texel(int face, int i, int j, const Rgb& c);
  // After texels change: copy each border texel from the nearest texel of the neighbour face.
  void update_borders();

  // The same size and texels, bit for bit (borders included).
  bool same_texels(const CubeMap& other) const { return size_ == other.size_ && faces_ == other.faces_; }
  // A 64-bit digest of the size and every texel (borders included): FNV-1a over 32-bit words
  // rather than bytes (four times fewer steps; ~20 ms at a 1024 face). Equal cubes have equal
  // fingerprints; different ones almost surely differ (an accident, not an attack, is the concern).
  std::uint64_t fingerprint() const;

  // Bilinear, seamless radiance in direction `dir` (need not be unit length).
  Rgb lookup(const Vec3f& dir) const;
  // Nearest-texel value (no filtering).
  Rgb lookup_nearest(const Vec3f& dir) const;

  // A face without its border as an RGB image (row 0 = t near 0).
  Image face_image(int face) const;
  void set_face_image(int face, const Image& img);  // img must be size x size RGB; borders not updated

 private:
  int size_ = 0;
  int stride_ = 0;                           // size + 2
  std::array<std::vector<float>, 6> faces_;  // (size+2)^2 RGB each
  float* ptr(int face, int i, int j) { return &faces_[face][(std::size_t(j + 1) * stride_ + (i + 1)) * 3]; }
  const float* ptr(int face, int i, int j) const { return &faces_[face][(std::size_t(j + 1) * stride_ + (i + 1)) * 3]; }
};

// Every texel (borders too) multiplied by a factor per channel: an exposure, a white balance.
CubeMap scaled(const CubeMap& cube, const Rgb& factor);

}  // namespace insitu
