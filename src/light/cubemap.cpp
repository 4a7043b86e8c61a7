#include "light/cubemap.h"

#include <algorithm>
#include <cassert>
#include <cstring>

namespace insitu {

const char* face_name(int face) {
  static const char* names[6] = {"+x", "-x", "up", "down", "+z", "-z"};  // as the scene file's shots
  return names[face];
}

FaceCoord project_to_face(int face, const Vec3f& r) {
  float sc, tc, ma;
  switch (face) {
    case kPosX:
      ma = r.x();
      sc = -r.z();
      tc = -r.y();
      break;
    case kNegX:
      ma = -r.x();
      sc = r.z();
      tc = -r.y();
      break;
    case kPosY:
      ma = r.y();
      sc = r.x();
      tc = r.z();
      break;
    case kNegY:
      ma = -r.y();
      sc = r.x();
      tc = -r.z();
      break;
    case kPosZ:
      ma = r.z();
      sc = r.x();
      tc = -r.y();
      break;
    default:
      ma = -r.z();
      sc = -r.x();
      tc = -r.y();
      break;
  }
  return {face, 0.5f * (sc / ma + 1.0f), 0.5f * (tc / ma + 1.0f)};
}

FaceCoord direction_to_face(const Vec3f& r) {
  const float ax = std::abs(r.x()), ay = std::abs(r.y()), az = std::abs(r.z());
  int face;
  if (ax >= ay && ax >= az)
    face = r.x() > 0 ? kPosX : kNegX;
  else if (ay >= az)
    face = r.y() > 0 ? kPosY : kNegY;
  else
    face = r.z() > 0 ? kPosZ : kNegZ;
  return project_to_face(face, r);
}

Vec3f face_to_direction(int face, float s, float t) {
  const float sc = 2.0f * s - 1.0f, tc = 2.0f * t - 1.0f;
  switch (face) {
    case kPosX:
      return {1.0f, -tc, -sc};
    case kNegX:
      return {-1.0f, -tc, sc};
    case kPosY:
      return {sc, 1.0f, tc};
    case kNegY:
      return {sc, -1.0f, -tc};
    case kPosZ:
      return {sc, -tc, 1.0f};
    default:
      return {-sc, -tc, -1.0f};
  }
}

Vec3f texel_direction(int face, int i, int j, int n) {
  return face_to_direction(face, (float(i) + 0.5f) / float(n), (float(j) + 0.5f) / float(n)).normalized();
}

CubeMap::CubeMap(int size) : size_(size), stride_(size + 2) {
  assert(size >= 1);
  for (auto& f : faces_) f.assign(std::size_t(stride_) * stride_ * 3, 0.0f);
}

Rgb CubeMap::texel(int face, int i, int j) const {
  const float* p = ptr(face, i, j);
  return {p[0], p[1], p[2]};
}

void CubeMap::set_texel(int face, int i, int j, const Rgb& c) {
  float* p = ptr(face, i, j);
  p[0] = c[0];
  p[1] = c[1];
  p[2] = c[2];
}

Rgb CubeMap::lookup_nearest(const Vec3f& dir) const {
  const FaceCoord fc = direction_to_face(dir);
  return texel(fc.face, nearest_texel_index(fc.s, size_), nearest_texel_index(fc.t, size_));
}

void CubeMap::update_borders() {
  const int n = size_;
  for (int f = 0; f < 6; ++f)
    for (int j = -1; j <= n; ++j)
      for (int i = -1; i <= n; ++i) {
        if (i >= 0 && i < n && j >= 0 && j < n) continue;
        const bool corner = (i < 0 || i >= n) && (j < 0 || j >= n);
        if (corner) {
          // Three faces meet at a cube corner. The corner border texel is the mean of their three
          // corner texels; then every face returns that same mean at the corner, and the two
          // faces along each edge agree all the way into the corner.
          const Vec3f d = face_to_direction(f, i < 0 ? 0.0f : 1.0f, j < 0 ? 0.0f : 1.0f);
          Rgb sum = Rgb::Zero();
          for (int axis = 0; axis < 3; ++axis) {
            const int g = 2 * axis + (d[axis] > 0 ? 0 : 1);
            const FaceCoord fc = project_to_face(g, d);
            sum += texel(g, nearest_texel_index(fc.s, n), nearest_texel_index(fc.t, n));
          }
          set_texel(f, i, j, sum / 3.0f);
          continue;
        }
        // The border texel's centre lies on the face's plane just past the edge; its direction
        // falls on the neighbour face, whose nearest texel is the one across the edge.
        const Vec3f d = face_to_direction(f, (float(i) + 0.5f) / float(n), (float(j) + 0.5f) / float(n));
        set_texel(f, i, j, lookup_nearest(d));
      }
}

Rgb CubeMap::lookup(const Vec3f& dir) const {
  const FaceCoord fc = direction_to_face(dir);
  // Texel centres sit at (i + 0.5)/n; x, y are continuous texel coordinates.
  const float x = fc.s * float(size_) - 0.5f, y = fc.t * float(size_) - 0.5f;
  const int i0 = std::clamp(int(std::floor(x)), -1, size_ - 1);
  const int j0 = std::clamp(int(std::floor(y)), -1, size_ - 1);
  const float wx = std::clamp(x - float(i0), 0.0f, 1.0f), wy = std::clamp(y - float(j0), 0.0f, 1.0f);
  const float* a = ptr(fc.face, i0, j0);
  const float* b = a + 3;
  const float* c = a + std::size_t(stride_) * 3;
  const float* d = c + 3;
  Rgb out;
  for (int k = 0; k < 3; ++k) out[k] = (1 - wy) * ((1 - wx) * a[k] + wx * b[k]) + wy * ((1 - wx) * c[k] + wx * d[k]);
  return out;
}

Image CubeMap::face_image(int face) const {
  Image img(size_, size_, 3);
  for (int j = 0; j < size_; ++j)
    for (int i = 0; i < size_; ++i) img.set_rgb(i, j, texel(face, i, j));
  return img;
}

void CubeMap::set_face_image(int face, const Image& img) {
  assert(img.width == size_ && img.height == size_ && img.channels >= 3);
  for (int j = 0; j < size_; ++j)
    for (int i = 0; i < size_; ++i) set_texel(face, i, j, img.rgb(i, j));
}

std::uint64_t CubeMap::fingerprint() const {
  std::uint64_t h = 14695981039346656037ull;
  auto mix = [&h](std::uint32_t w) { h = (h ^ w) * 1099511628211ull; };
  mix(std::uint32_t(size_));
  for (const std::vector<float>& face : faces_)
    for (const float v : face) {
      std::uint32_t w = 0;
      std::memcpy(&w, &v, sizeof w);
      mix(w);
    }
  return h;
}

CubeMap scaled(const CubeMap& cube, const Rgb& factor) {
  CubeMap out(cube.size());
  for (int f = 0; f < 6; ++f)
    for (int j = -1; j <= cube.size(); ++j)
      for (int i = -1; i <= cube.size(); ++i) out.set_texel(f, i, j, cube.texel(f, i, j) * factor);
  return out;
}

}  // namespace insitu
