// Camera calibration from five or more 2D–3D control points (docs/calibration.md).
//
// The descendant of Bogart's View Correlation (Graphics Gems II, 1991), which ran Newton
// iterations on the reprojection error from a view the user set up by hand. Here:
//   1. no starting guess: DLT for six or more non-coplanar points, and PnP (OpenCV SQPnP) over a
//      sweep of focal lengths for any five or more points; the best start by reprojection error;
//   2. Levenberg–Marquardt (Ceres) on the reprojection error with a Cauchy loss, after which points
//      whose residual is far beyond the others' (5 robust σ, at least 3 px) are named as outliers
//      and left out of the final, plain least-squares fit;
//   3. nested models f ⊂ f+c ⊂ f+c+a; `auto` keeps the richer model only when the extra-sum-of-
//      squares F-test says the fit improved beyond what noise explains (α = 0.01);
//   4. standard deviations from Ceres's covariance scaled by the residual variance, propagated to
//      the derived quantities and to a floor point at the insertion spot.
// All fitting happens in normalized frames, so millimetres, kilometres, 64-pixel and 12000-pixel
// images are conditioned alike.
#pragma once
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/error.h"
#include "calib/control_points.h"

namespace insitu {

enum class CameraModel { kF, kFC, kFCA };
const char* model_name(CameraModel model);                        // "f", "f+c", "f+c+a"
std::optional<CameraModel> parse_model(const std::string& name);  // nullopt unless one of those
int model_parameter_count(CameraModel model);                     // 7, 9, 10

struct CalibrationOptions {
  std::optional<CameraModel> model;      // nullopt: choose automatically
  std::optional<Vec3d> insertion_world;  // default: below the points' centroid on y = 0
  double significance = 0.01;            // of the F-test in auto mode
};

struct PointResidual {
  std::string name;
  Vec2d uv_px = Vec2d::Zero();
  Vec2d residual_px = Vec2d::Zero();  // projected − clicked
  bool outlier = false;
  bool behind = false;
};

struct ModelFit {
  CameraModel model = CameraModel::kF;
  bool fitted = false;
  std::string note;    // why it was not fitted, or the test that decided
  double rss_px2 = 0;  // sum of squared residuals over the inliers
  int residuals = 0;   // 2 × inliers
  double rms_px = 0;
  double p_value = -1;  // of the F-test against the model chosen before it (−1: not tested)
};

struct CalibrationUncertainty {
  bool known = false;  // false when there is no redundancy (or the covariance is singular)
  double fx_px = 0, fy_px = 0, cx_px = 0, cy_px = 0, aspect = 0;
  Vec3d eye_world = Vec3d::Zero();
  double hfov_deg = 0, view_direction_deg = 0, roll_deg = 0;
};

struct CalibrationFitState;  // fit_state.h: what object_uncertainty.h asks questions of

struct CalibrationResult {
  Camera camera;
  CameraModel model = CameraModel::kF;
  std::string selection;  // how the model was chosen
  std::vector<ModelFit> fits;
  std::vector<PointResidual> points;
  double rms_px = 0;    // over the inliers
  double sigma_px = 0;  // residual standard deviation, sqrt(RSS / (m − k))
  int inliers = 0;
  bool coplanar = false;
  CalibrationUncertainty sigma;
  Vec3d insertion_world = Vec3d::Zero();
  Vec2d insertion_px = Vec2d::Zero();
  double insertion_sigma_px = 0;           // 1σ along the major axis of the projected noise
  double insertion_noise_radius95_px = 0;  // the 95 % radius of the noise alone
  // The 95 % radius with the model's own error, as at the objects' corners (object_uncertainty.h):
  // max(noise, shift to the next richer model + its radius); infinite when nothing bounds it.
  double insertion_radius95_px = 0;
  double insertion_model_shift_px = 0;
  Warnings warnings;  // each without a location: the caller adds the points file's
  std::shared_ptr<const CalibrationFitState> state;
};

// Throws InputError for fewer than five points, non-finite values, points that cannot determine
// a camera (all coincident or collinear), or a model the points cannot support.
CalibrationResult calibrate(const std::vector<ControlPoint>& points, int width, int height,
                            const CalibrationOptions& options = {});

// camera.json: camera_to_json plus a "calibration" section with the report.
nlohmann::json calibration_to_json(const CalibrationResult& result);
// The report as text, for people.
std::string calibration_report(const CalibrationResult& result);

}  // namespace insitu
