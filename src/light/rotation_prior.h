// What the fits that turn shots share (shot_registration.cpp, room_lines.cpp): a rotation kept
// as its rotation vector (angle-axis, Ceres's parametrisation), its matrix, and the prior that
// holds it near the nominal direction, |log R| / σ_p.
#pragma once
#include <ceres/rotation.h>

#include <array>

#include "core/math.h"

namespace insitu {

// log R / σ_p: the rotation vector against the nominal direction.
struct RotationPrior {
  double inv_sigma;
  template <typename T>
  bool operator()(const T* aa, T* r) const {
    for (int k = 0; k < 3; ++k) r[k] = aa[k] * T(inv_sigma);
    return true;
  }
};

inline Mat3d rotation_of(const std::array<double, 3>& aa) {
  Mat3d R;
  ceres::AngleAxisToRotationMatrix(aa.data(), ceres::ColumnMajorAdapter3x3(R.data()));
  return R;
}

}  // namespace insitu
