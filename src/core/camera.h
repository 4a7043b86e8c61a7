// The pinhole camera in the OpenCV convention (DESIGN.md "Camera").
//
//   X_c = R X_w + t            camera x right, y down, z forward
//   u = fx X_c/Z_c + cx,  v = fy Y_c/Z_c + cy
//
// Pixel coordinates: (0,0) is the top-left corner of the top-left pixel; the centre of pixel
// (i, j) is (i+0.5, j+0.5).
#pragma once
#include <nlohmann/json_fwd.hpp>

#include "core/math.h"

namespace insitu {

struct Ray {
  Vec3f origin;
  Vec3f dir;  // unit length
};

struct Camera {
  int width = 0, height = 0;              // image size in pixels
  double fx = 1, fy = 1, cx = 0, cy = 0;  // intrinsics in pixels
  Mat3d R_cam_from_world = Mat3d::Identity();
  Vec3d t_cam_from_world = Vec3d::Zero();

  // eye at `eye_world`, looking at `look_world`, `up_world` roughly up in the image; square
  // pixels, principal point at the image centre, horizontal field of view `hfov_deg`.
  static Camera look_at(const Vec3d& eye_world, const Vec3d& look_world, const Vec3d& up_world, double hfov_deg,
                        int width, int height);

  Vec3d to_camera(const Vec3d& p_world) const { return R_cam_from_world * p_world + t_cam_from_world; }
  // Pixel position of a world point; *depth_m receives Z_c (<= 0: behind the camera).
  Vec2d project(const Vec3d& p_world, double* depth_m = nullptr) const;
  // The world point at camera depth Z_c = depth_m that projects to pixel `uv`.
  Vec3d unproject(const Vec2d& uv, double depth_m) const;
  // The primary ray through pixel position `uv` (in pixels, any sub-pixel position).
  Ray ray(const Vec2d& uv) const;

  Vec3d eye_world() const { return -R_cam_from_world.transpose() * t_cam_from_world; }
  Vec3d forward_world() const { return R_cam_from_world.row(2).transpose(); }
  Vec3d up_world() const { return -R_cam_from_world.row(1).transpose(); }
  double hfov_deg() const;  // full horizontal field of view through the image edges
  double vfov_deg() const;
};

// camera.json (written by `insitu calibrate` later, readable by people): intrinsics, pose
// and, for people, eye/look/up and both fields of view.
nlohmann::json camera_to_json(const Camera& cam);

}  // namespace insitu
