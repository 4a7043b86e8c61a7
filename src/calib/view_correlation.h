// The legacy View Correlation parameter set (Bogart, "View Correlation", Graphics Gems II, 1991),
// in the text layout of its viewfind program, so that results can be compared with old projects:
//
//   eye.x eye.y eye.z
//   look.x look.y look.z
//   up.x up.y up.z
//   d_over_s aspect
//   halfx halfy xcenter ycenter
//   n
//   x y z sx sy          (n lines: a 3D point and its screen position)
//
// Its camera: z = normalize(eye − look), x = normalize(up × z), y = z × x (y up, looking down −z),
// and a point projects to
//   sx = xcenter − d_over_s·halfx·x_v/z_v,   sy = ycenter − aspect·d_over_s·halfx·y_v/z_v
// with (x_v, y_v, z_v) the point relative to the eye in that frame. sy grows upward: the screen
// origin is the bottom-left corner (we take screen positions as continuous coordinates with (0,0)
// at the bottom-left corner of the image, height 2·halfy). In our convention:
//   fx = d_over_s·halfx,  fy = aspect·fx,  cx = xcenter,  cy = 2·halfy − ycenter,
//   R rows = (x, −y, −z).
#pragma once
#include <string>
#include <vector>

#include "core/camera.h"
#include "calib/control_points.h"

namespace insitu {

struct ViewCorrelation {
  Vec3d eye = Vec3d::Zero(), look = Vec3d(0, 0, -1), up = Vec3d(0, 1, 0);
  double d_over_s = 1, aspect = 1, halfx = 1, halfy = 1, xcenter = 1, ycenter = 1;
  std::vector<ControlPoint> points;  // uv in our top-left convention
};

ViewCorrelation read_view_correlation(const std::string& path);
void write_view_correlation(const std::string& path, const ViewCorrelation& vc);

Camera camera_from_view_correlation(const ViewCorrelation& vc);
ViewCorrelation view_correlation_from_camera(const Camera& cam, const std::vector<ControlPoint>& points);

}  // namespace insitu
