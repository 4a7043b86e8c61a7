// Equirectangular (latitude-longitude) environment images, in the layout Blender/Cycles reads
// and ../shared/data/hdri uses. In Blender's Z-up frame the centre column looks along +X, u grows
// with decreasing azimuth atan2(y, x), and the top row is straight up. Blender (x, y, z) is our
// Y-up world (x, -z, y) (the glTF/OBJ export convention), so for a world direction d:
//   phi = atan2(-d.z, d.x),  u = 0.5 - phi/(2π),  v = acos(d.y)/π
// (u, v in [0,1], u across the width, v down the height).
#pragma once
#include "light/cubemap.h"
#include "core/image.h"

namespace insitu {

Vec2f direction_to_equirect(const Vec3f& dir_unit);
Vec3f equirect_to_direction(float u, float v);
// Bilinear lookup, wrapping in u and clamping in v.
Rgb equirect_lookup(const Image& img, const Vec3f& dir_unit);
// Resamples onto a cube of `face_size`, averaging ss x ss bilinear samples per texel.
CubeMap cube_from_equirect(const Image& img, int face_size, int ss = 2);

// Cube images on disk: a vertical strip of the six faces in the order +X, −X, +Y, −Y, +Z, −Z,
// each face in the cube convention (width n, height 6n).
CubeMap cube_from_strip(const Image& strip);
Image cube_to_strip(const CubeMap& cube);

}  // namespace insitu
