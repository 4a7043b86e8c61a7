#include "core/math.h"

#include <Eigen/SVD>

namespace insitu {

Mat3d nearest_rotation(const Mat3d& M) {
  const Eigen::JacobiSVD<Mat3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

}  // namespace insitu
