#include "calib/calibration_summary.h"

namespace insitu {

CalibrationSummary summarize_calibration(const CalibrationResult& r, const std::vector<NamedBox>& boxes) {
  CalibrationSummary s{calibration_report(r), calibration_to_json(r)};
  if (boxes.empty()) return s;
  std::vector<ObjectUncertainty> objects;
  for (const auto& [name, corners] : boxes) objects.push_back(object_uncertainty(r, name, corners));
  const std::optional<ClickHint> hint = suggest_next_click(r, objects);
  s.report += object_uncertainty_report(objects, hint);
  const std::string warning = outside_clicks_warning(objects, hint);
  if (!warning.empty()) s.report += "warning: " + warning + "\n";
  s.camera_json["calibration"]["at_objects"] = object_uncertainty_json(objects, hint);
  return s;
}

}  // namespace insitu
