#include "calib/fspy.h"

#include <cmath>
#include <fmt/format.h>

#include "core/json_reader.h"
#include "core/math.h"

namespace insitu {

namespace {

// Blender's Z-up world to insitu's Y-up world: (x, y, z) -> (x, z, −y).
Mat3d insitu_from_blender() {
  Mat3d A;
  A << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  return A;
}

// The camera's pose from fSpy's camera-to-world matrix.
void set_pose(const JsonValue& rows, Camera& cam, Warnings* warnings) {
  const Mat4d M = rows.mat4();
  if ((M.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-9)
    rows.fail("not a camera transform: its last row must be (0, 0, 0, 1)");
  const Mat3d R_world_from_gl = checked_rotation(M.topLeftCorner<3, 3>(), rows, warnings);
  const Mat3d gl_from_cv = Vec3d(1, -1, -1).asDiagonal();
  const Mat3d R_world_from_cv = insitu_from_blender() * R_world_from_gl * gl_from_cv;
  const Vec3d eye_world = insitu_from_blender() * M.topRightCorner<3, 1>();
  cam.R_cam_from_world = R_world_from_cv.transpose();
  cam.t_cam_from_world = -cam.R_cam_from_world * eye_world;
}

}  // namespace

Camera camera_from_fspy(const std::string& path, int width, int height, Warnings* warnings) {
  const json doc = read_json_file(path);
  JsonObject o(JsonValue(doc, path, "$"));
  const double w = double(o.get("imageWidth").integer(1, 1 << 20)),
               h = double(o.get("imageHeight").integer(1, 1 << 20));
  if (std::abs((w / h) / (double(width) / height) - 1) > 0.01)
    o.get("imageWidth")
        .fail(fmt::format("fSpy's image is {}x{}, the photo {}x{}: not the same aspect ratio", w, h, width, height));
  const JsonValue hfov = o.get("horizontalFieldOfView");
  const double f_rel = 1.0 / std::tan(0.5 * hfov.number(1e-6, M_PI - 1e-6));
  if (auto rel = o.find("relativeFocalLength"))
    if (std::abs(rel->number() / f_rel - 1) > 1e-4)
      rel->fail(fmt::format("disagrees with horizontalFieldOfView (which gives {:.6g})", f_rel));
  JsonObject pp(o.get("principalPoint"));
  const double px = pp.get("x").number(-1e3, 1e3), py = pp.get("y").number(-1e3, 1e3);
  pp.finish();
  Camera cam;
  cam.width = width;
  cam.height = height;
  const double half_long_px = 0.5 * std::max(width, height);
  cam.fx = cam.fy = f_rel * half_long_px;
  cam.cx = 0.5 * width + px * half_long_px;
  cam.cy = 0.5 * height - py * half_long_px;
  JsonObject transform(o.get("cameraTransform"));
  set_pose(transform.get("rows"), cam, warnings);
  transform.finish();
  // What fSpy also exports, not needed here.
  for (const char* informational : {"viewTransform", "verticalFieldOfView", "vanishingPoints", "vanishingPointAxes"})
    o.find(informational);
  o.finish();
  return cam;
}

}  // namespace insitu
