#include "interop/blender_camera.h"

#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace insitu {

Mat3d blender_from_insitu() {
  Mat3d B;
  B << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  return B;
}

Mat4d blender_camera_to_world(const Camera& c) {
  Mat4d M = Mat4d::Identity();
  M.topLeftCorner<3, 3>() = blender_from_insitu() * c.R_cam_from_world.transpose() * Vec3d(1, -1, -1).asDiagonal();
  M.topRightCorner<3, 1>() = blender_from_insitu() * c.eye_world();
  return M;
}

namespace {

std::string matrix_rows(const Mat4d& M) {
  std::string rows;
  for (int r = 0; r < 3; ++r)
    rows += fmt::format("    ({:.17g}, {:.17g}, {:.17g}, {:.17g}),\n", M(r, 0), M(r, 1), M(r, 2), M(r, 3));
  return rows + "    (0.0, 0.0, 0.0, 1.0),\n";
}

}  // namespace

std::string blender_camera_lines(const Camera& c, const std::string& photo_path) {
  // Pixel aspect ax/ay = fy/fx, one of them 1; Blender measures lens and shift in aspect-corrected
  // units, W·ax by H·ay, along the longer of the two.
  const double ax = std::max(1.0, c.fy / c.fx), ay = std::max(1.0, c.fx / c.fy);
  const double Lc = std::max(c.width * ax, c.height * ay);
  const double lens_mm = c.fx * ax * 36.0 / Lc;
  const double shift_x = (0.5 * c.width - c.cx) * ax / Lc, shift_y = (c.cy - 0.5 * c.height) * ay / Lc;
  std::string s = fmt::format(
      "scene.render.resolution_x = {}\nscene.render.resolution_y = {}\nscene.render.resolution_percentage = 100\n",
      c.width, c.height);
  s += fmt::format("scene.render.pixel_aspect_x = {:.17g}\nscene.render.pixel_aspect_y = {:.17g}\n", ax, ay);
  s += "data = bpy.data.cameras.new('insitu camera')\n";
  s += "data.type = 'PERSP'\ndata.sensor_fit = 'AUTO'\ndata.sensor_width = 36.0\n";
  s += fmt::format("data.lens = {:.17g}\ndata.shift_x = {:.17g}\ndata.shift_y = {:.17g}\n", lens_mm, shift_x, shift_y);
  s += "camera = bpy.data.objects.new('insitu camera', data)\nscene.collection.objects.link(camera)\n";
  s += "camera.matrix_world = Matrix((\n" + matrix_rows(blender_camera_to_world(c)) + "))\nscene.camera = camera\n";
  if (!photo_path.empty()) {
    const std::string abs = std::filesystem::absolute(photo_path).lexically_normal().string();
    s += fmt::format(
        "background = data.background_images.new()\nbackground.image = bpy.data.images.load({}, check_existing=True)\n",
        nlohmann::json(abs).dump());
    s += "data.show_background_images = True\n";
  }
  return s;
}

std::string blender_camera_script(const Camera& c, const std::string& photo_path) {
  std::string s = "# Written by insitu (src/interop/blender_camera.h): the calibrated camera in Blender.\n";
  s += "import bpy\nfrom mathutils import Matrix\n\nscene = bpy.context.scene\n";
  return s + blender_camera_lines(c, photo_path);
}

}  // namespace insitu
