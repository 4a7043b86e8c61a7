// The residual of one control point for Ceres (in the style of the Ceres examples): the data in
// members, a Create() factory, autodiff. Frames are normalized (calibration.cpp): image
// coordinates centred on the image and divided by half its larger side, world coordinates centred
// on the points' centroid and divided by their RMS distance from it.
//
//   p_cam = R(rotation_aa) · p_world + t
//   r = ( f·p_cam.x/p_cam.z + cx − u ,  a·f·p_cam.y/p_cam.z + cy − v )
//
// intrinsics = [f, cx, cy, a]; the camera models hold some of them constant.
#pragma once
#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>

#include "core/math.h"

namespace insitu {

struct ReprojectionCost {
  ReprojectionCost(const Vec2d& uv_norm, const Vec3d& p_world_norm) : uv_norm_(uv_norm), p_world_norm_(p_world_norm) {}

  template <typename T>
  bool operator()(const T* const rotation_aa, const T* const translation, const T* const intrinsics,
                  T* residuals) const {
    const T p_world[3] = {T(p_world_norm_.x()), T(p_world_norm_.y()), T(p_world_norm_.z())};
    T p_cam[3];
    ceres::AngleAxisRotatePoint(rotation_aa, p_world, p_cam);
    for (int k = 0; k < 3; ++k) p_cam[k] += translation[k];
    const T& f = intrinsics[0];
    residuals[0] = f * p_cam[0] / p_cam[2] + intrinsics[1] - T(uv_norm_.x());
    residuals[1] = intrinsics[3] * f * p_cam[1] / p_cam[2] + intrinsics[2] - T(uv_norm_.y());
    return true;
  }

  static ceres::CostFunction* Create(const Vec2d& uv_norm, const Vec3d& p_world_norm) {
    return new ceres::AutoDiffCostFunction<ReprojectionCost, 2, 3, 3, 4>(new ReprojectionCost(uv_norm, p_world_norm));
  }

 private:
  Vec2d uv_norm_;
  Vec3d p_world_norm_;
};

}  // namespace insitu
