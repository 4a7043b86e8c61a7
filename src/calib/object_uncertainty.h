// The calibration's uncertainty where the furniture stands (docs/calibration.md).
//
// At each corner of an object's bounding box (the lowest four are its feet), in pixels:
//   - noise: the 95 % radius of the projected covariance of the chosen model,
//       r_noise = sqrt(χ²₂(0.95) · λmax(J Σ_M Jᵀ));
//   - the model's own error: the chosen model M fixes parameters (the principal point at the image
//     centre, square pixels) that the points may simply not determine. With M' the next richer
//     model (f ⊂ f+c ⊂ f+c+a) fitted to the same points, the truth lies within r'_95 of π_M'(x)
//     with 95 % probability if M' holds, hence within |π_M'(x) − π_M(x)| + r'_95 of π_M(x); and
//     within r_noise of it if M holds. Since M ⊂ M', the truth is one of the two cases, so
//       r_95 = max(r_noise, |π_M'(x) − π_M(x)| + r'_95)
//     covers it with at least 95 % probability either way (to first order). When M' cannot be
//     fitted (coplanar points, too few points), the model's error is not bounded, and that is said.
// The object's radius is its worst corner's. An object outside the clicks' span (a corner outside
// the convex hull of their pixels, or nearer or farther than all of them) is flagged, and
// suggest_next_click names the floor point whose click would most reduce the variance at the
// objects (Woodbury update of the richer model's covariance by one more observation).
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "calib/calibration.h"

namespace insitu {

struct NamedPoint {
  std::string name;
  Vec3d p_world = Vec3d::Zero();
};

struct PointUncertainty {
  NamedPoint point;
  Vec2d uv_px = Vec2d::Zero();
  double noise_sigma_px = 0;     // 1σ along the major axis, the chosen model, noise only
  double noise_radius95_px = 0;  // the 95 % radius of that alone
  double model_shift_px = 0;     // |π_M'(x) − π_M(x)|: 0 without a richer model
  double radius95_px = 0;        // r_95 above (infinite when nothing bounds it)
  bool outside_clicks = false;
};

struct ObjectUncertainty {
  std::string name;
  std::vector<PointUncertainty> points;
  std::size_t worst = 0;   // the point with the largest radius95_px
  std::string model_note;  // "against f+c", or why the model's own error is not bounded
  std::string outside;     // empty, or why the object lies outside the clicks' span
  double radius95_px() const { return points.empty() ? 0 : points[worst].radius95_px; }
};

// The eight corners of a box, named by their sides ("feet −x−z", …, "top +x+z").
std::vector<NamedPoint> box_corners(const Vec3d& lo_world, const Vec3d& hi_world);

// Throws std::logic_error when the result has no fit state (not from calibrate()).
ObjectUncertainty object_uncertainty(const CalibrationResult& calibration, const std::string& name,
                                     const std::vector<NamedPoint>& points);

struct ClickHint {
  Vec3d p_world = Vec3d::Zero();
  Vec2d uv_px = Vec2d::Zero();
  double sigma_before_px = 0, sigma_after_px = 0;  // worst 1σ at the objects under the model used
  std::string model;                               // the model whose variance is predicted
};

// The point on the floor (the plane y = the lowest foot) inside the photo whose click, with the
// residual σ̂, would most reduce the summed variance at the objects' points; nullopt without a
// covariance or when no floor point is in view.
std::optional<ClickHint> suggest_next_click(const CalibrationResult& calibration,
                                            const std::vector<ObjectUncertainty>& objects);

}  // namespace insitu

namespace insitu {

// For people: a line per object (its 95 % radius, the worst corner, noise and the model's share),
// the objects outside the clicks' span, and the hint.
std::string object_uncertainty_report(const std::vector<ObjectUncertainty>& objects,
                                      const std::optional<ClickHint>& hint);
// For programs: {"objects": [...], "click_next": {...} or null}.
nlohmann::json object_uncertainty_json(const std::vector<ObjectUncertainty>& objects,
                                       const std::optional<ClickHint>& hint);
// The warning for objects outside the clicks' span ("" when none is), with the hint.
std::string outside_clicks_warning(const std::vector<ObjectUncertainty>& objects, const std::optional<ClickHint>& hint);

}  // namespace insitu
