#include "core/camera.h"

#include <nlohmann/json.hpp>

namespace insitu {

Camera Camera::look_at(const Vec3d& eye_world, const Vec3d& look_world, const Vec3d& up_world, double hfov_deg,
                       int width, int height) {
  Camera cam;
  cam.width = width;
  cam.height = height;
  // fx = (W/2) / tan(hfov/2); square pixels; principal point at the image centre.
  cam.fx = cam.fy = 0.5 * width / std::tan(0.5 * deg_to_rad(hfov_deg));
  cam.cx = 0.5 * width;
  cam.cy = 0.5 * height;
  // Rows of R are the camera axes in world coordinates: z forward, x = z × up (right),
  // y = z × x (down); right-handed because x × y = z.
  const Vec3d z = (look_world - eye_world).normalized();
  const Vec3d x = z.cross(up_world).normalized();
  const Vec3d y = z.cross(x);
  cam.R_cam_from_world.row(0) = x.transpose();
  cam.R_cam_from_world.row(1) = y.transpose();
  cam.R_cam_from_world.row(2) = z.transpose();
  cam.t_cam_from_world = -cam.R_cam_from_world * eye_world;
  return cam;
}

Vec2d Camera::project(const Vec3d& p_world, double* depth_m) const {
  const Vec3d p_cam = to_camera(p_world);
  if (depth_m) *depth_m = p_cam.z();
  return {fx * p_cam.x() / p_cam.z() + cx, fy * p_cam.y() / p_cam.z() + cy};
}

Vec3d Camera::unproject(const Vec2d& uv, double depth_m) const {
  const Vec3d p_cam((uv.x() - cx) / fx * depth_m, (uv.y() - cy) / fy * depth_m, depth_m);
  return R_cam_from_world.transpose() * (p_cam - t_cam_from_world);
}

Ray Camera::ray(const Vec2d& uv) const {
  const Vec3d d_cam((uv.x() - cx) / fx, (uv.y() - cy) / fy, 1.0);
  const Vec3d d_world = (R_cam_from_world.transpose() * d_cam).normalized();
  return {eye_world().cast<float>(), d_world.cast<float>()};
}

// The field of view through the image edges, which need not be symmetric about the axis.
double Camera::hfov_deg() const { return rad_to_deg(std::atan(cx / fx) + std::atan((width - cx) / fx)); }
double Camera::vfov_deg() const { return rad_to_deg(std::atan(cy / fy) + std::atan((height - cy) / fy)); }

nlohmann::json camera_to_json(const Camera& cam) {
  using nlohmann::json;
  json R = json::array();
  for (int r = 0; r < 3; ++r)
    R.push_back({cam.R_cam_from_world(r, 0), cam.R_cam_from_world(r, 1), cam.R_cam_from_world(r, 2)});
  const Vec3d eye = cam.eye_world(), fwd = cam.forward_world(), up = cam.up_world();
  return json{
      {"width", cam.width},
      {"height", cam.height},
      {"intrinsics", {{"fx", cam.fx}, {"fy", cam.fy}, {"cx", cam.cx}, {"cy", cam.cy}}},
      {"pose", {{"R", R}, {"t", {cam.t_cam_from_world.x(), cam.t_cam_from_world.y(), cam.t_cam_from_world.z()}}}},
      {"eye", {eye.x(), eye.y(), eye.z()}},
      {"look", {eye.x() + fwd.x(), eye.y() + fwd.y(), eye.z() + fwd.z()}},
      {"up", {up.x(), up.y(), up.z()}},
      {"hfov_deg", cam.hfov_deg()},
      {"vfov_deg", cam.vfov_deg()},
  };
}

}  // namespace insitu
