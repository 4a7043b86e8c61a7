// Previews for people: a cube unfolded as a cross, as seen from inside the room.
//
//            [ +Y ]
//   [ −X ] [ −Z ] [ +X ] [ +Z ]
//            [ −Y ]
//
// The middle row is the walls as a panorama facing −Z (left, front, right, back); ceiling and
// floor are shown with their edge toward −Z against the front wall. Each square is a 90° view
// (sixshot.h's render_shot), so nothing is mirrored. Values are scaled by `exposure` and encoded
// with the sRGB curve (clipped).
#pragma once
#include "light/cubemap.h"
#include "core/image.h"

namespace insitu {

// The cross's squares: each face's column and row, in squares of the face's size.
struct CrossSquare {
  int face, col, row;
};
constexpr CrossSquare kCrossLayout[6] = {{kNegX, 0, 1}, {kNegZ, 1, 1}, {kPosX, 2, 1},
                                         {kPosZ, 3, 1}, {kPosY, 1, 0}, {kNegY, 1, 2}};

// The exposure that puts the cube's median luminance at 0.18.
double preview_exposure(const CubeMap& cube);
// `face_px`: pixels a face of the cross (0: the cube's own size).
Image cube_cross_preview(const CubeMap& cube, double exposure, int face_px = 0);
// An equirectangular image (width 4n, height 2n) of the cube, linear.
Image cube_to_equirect(const CubeMap& cube);

}  // namespace insitu
