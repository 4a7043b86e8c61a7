// The directions no shot (or panorama) covered, taken from the photo where it sees the room there.
//
// Shots from a phone's main camera (about 70° across, 4:3) leave most of each cube face
// uncovered, and the assembly fills those texels smoothly from their neighbours
// (light/sixshot.h fill_uncovered). That fill is no measurement, and it is not neutral: inverse
// lighting reads a clipped source's scale from the contrast it makes across the photo, with each
// surface's albedo free, so a fill brighter than the room flattens that contrast and the fit
// raises the sources to restore it. In the closed room with the main camera's handheld JPEG shots
// the fill held 1.41× the true light above the window and 1.22× on the ceiling, and the objects
// came out 1.30× too bright (error 25.8 %); with the true light in the uncovered texels the same
// fit gave 0.97 (8.0 %) (docs/validation.md, "The uncovered directions").
//
// The photo sees the same room. A Lambertian wall has one radiance whatever it is seen from, so
// the wall point q of the room box that the capture point c saw along an uncovered direction
// ω = (q − c)/|q − c| shows in the photo the radiance c would have seen. Per uncovered texel: q
// at k × k points of its footprint, one per two photo pixels across it (k from 1 to 4), each
// projected into the photo and sampled bilinearly; the texel takes their mean where all of them
// fall in the frame, on unclipped pixels, on a wall (not through an opening, whose outside the
// photo sees from elsewhere). The photo's values are
// brought to the shots' level by the median of Y(light)/Y(photo) over the photo pixels whose wall
// point the shots did see (unclipped in both): an exposure from EXIF or an estimate is not exact,
// and the texels must match the shots' beside them. Without kPhotoFillMinPixels such pixels the
// level is unknown and the photo fills nothing. The other uncovered texels are then filled again
// from their neighbours, the photo's among them.
//
// A partial panorama (a phone's sweep, 360° × about 90°) leaves the ceiling and the floor unseen
// and stretches its edges there (light/panorama.h); its unseen texels are filled the same way.
//
// Only with a room box (without one a photo pixel's direction from c is unknown) and with the
// photo's camera inside it (then every wall point in the frame is in its view: the box is convex).
// A real room's furniture or a glossy wall shows in the photo as the wall would not; the median
// keeps it from the level, not from the texels it falls on.
#pragma once
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "light/cubemap.h"
#include "light/room_light.h"

namespace insitu {

inline constexpr int kPhotoFillMinPixels = 100;

struct PhotoFill {
  long uncovered = 0;    // texels no shot covered
  long from_photo = 0;   // of them, taken from the photo
  double level = 1;      // Y(light)/Y(photo): the photo's values are multiplied by it
  int level_pixels = 0;  // photo pixels that set it
  std::string reason;    // when the photo fills nothing: why
};

// `covered`: per texel of `radiance` ((face·n + j)·n + i), whether a shot covered it
// (EnvironmentInfo::covered); `clipped`: the light's clipped cube, or null. `radiance` is in the
// photo's unit and colour (after the white balance).
PhotoFill fill_from_photo(CubeMap& radiance, const std::vector<bool>& covered, const CubeMap* clipped,
                          const RoomBox& box, const Camera& camera, const Image& photo_linear,
                          const Image& photo_clipped);

}  // namespace insitu
