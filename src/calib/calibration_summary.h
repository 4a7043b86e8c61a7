// What `insitu calibrate` prints and writes, for the CLI and the C API alike: the report, with the
// uncertainty at each object's bounding box and where to click next when boxes are given, and
// camera.json with the same under "calibration"."at_objects".
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "calib/calibration.h"
#include "calib/object_uncertainty.h"

namespace insitu {

using NamedBox = std::pair<std::string, std::vector<NamedPoint>>;  // a name and its 8 corners

struct CalibrationSummary {
  std::string report;  // for people, as the CLI prints it
  nlohmann::json camera_json;
};

CalibrationSummary summarize_calibration(const CalibrationResult& result, const std::vector<NamedBox>& boxes);

}  // namespace insitu
