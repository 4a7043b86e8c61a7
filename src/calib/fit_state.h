// What a calibration keeps to answer questions after the fit (object_uncertainty.h): the chosen
// model's and the next richer model's parameters with their covariances, and where the clicks lie.
// Internal to src/calib.
#pragma once
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "calib/camera_params.h"

namespace insitu {

// One model's fit: its parameters and their covariance (normalized units, tangent space: the
// parameters the model holds fixed have zero rows and columns), scaled by its own residual
// variance σ̂² = RSS/(m − k).
struct ModelCovariance {
  CameraModel model = CameraModel::kF;
  calib_detail::Params params;
  Eigen::Matrix<double, 10, 10> C = Eigen::Matrix<double, 10, 10>::Zero();
  double sigma_norm = 0;  // σ̂ of one image coordinate, normalized
};

struct CalibrationFitState {
  calib_detail::Frames frames;
  std::optional<ModelCovariance> chosen;            // nullopt: no redundancy or a singular covariance
  std::optional<ModelCovariance> richer;            // the next richer model, when the points fit it
  std::string richer_note;                          // why there is none (empty when there is)
  std::vector<Vec2d> clicks_hull_px;                // the convex hull of the inliers' pixels (fewer than 3: none)
  double click_depth_min = 0, click_depth_max = 0;  // their depths along the optical axis
};

// The covariance of a model fitted to `inliers` (Ceres's (JᵀJ)⁻¹ in the tangent space, dense SVD)
// scaled by σ̂² = rss_px2 / (m − k); nullopt when m ≤ k, the fit is exact or JᵀJ is singular.
std::optional<ModelCovariance> model_covariance(const calib_detail::Params& params, CameraModel model,
                                                const std::vector<calib_detail::NormPoint>& inliers, double rss_px2,
                                                const calib_detail::Frames& frames);

}  // namespace insitu
