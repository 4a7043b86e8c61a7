// What the points panel draws over the photo through the current camera: the local
// scene's planes as a grid and the room box's twelve edges, so that a wrong point shows at once
// as a grid that does not lie on the floor.
#pragma once
#include <optional>
#include <vector>

#include "core/camera.h"
#include "core/math.h"

namespace insitu {

struct Segment3 {
  Vec3d a_world, b_world;
};
struct Segment2 {
  Vec2d a_px, b_px;
};

// The twelve edges of the axis-aligned box [lo, hi].
std::vector<Segment3> box_edges(const Vec3d& lo_world, const Vec3d& hi_world);

// Grid lines on the plane through `point` with normal `normal`, centred on the point of the plane
// nearest `centre`, `half_size` metres to each side, about 8 lines each way at a spacing of
// 1, 2 or 5 × 10^k metres (so millimetre and kilometre scenes alike get a readable grid).
std::vector<Segment3> plane_grid(const Vec3d& point_world, const Vec3d& normal_world, const Vec3d& centre_world,
                                 double half_size_m);

// The segment's image, clipped to the part in front of the camera (Z_c > 0); nullopt when none is.
std::optional<Segment2> project_segment(const Camera& camera, const Segment3& s);

}  // namespace insitu
