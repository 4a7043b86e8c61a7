// Each shot as the render report and the studio's shots panel describe it: where it was aimed
// (registration, light/shot_registration.h), how the room's lines anchored it (light/room_lines.h)
// and the gain that matched it to its neighbours (light/shot_gains.h).
#pragma once
#include <nlohmann/json.hpp>

#include "light/environment.h"
#include "light/environment_spec.h"

namespace insitu {

// A shot's aim as registration found it; null with "register": "none".
nlohmann::json registration_json(const std::optional<Registration>& r, int face);
// How the room's lines anchored a shot's aim; null without a room box.
nlohmann::json room_lines_json(const std::optional<LineAnchor>& a, int face);
// How the photo anchored a shot's aim; null with a room box or without the photo's camera.
nlohmann::json photo_anchor_json(const std::optional<PhotoAnchor>& a, int face);
// Shot `face` of the environment: its files, turn, coverage, clipping, registration, room lines
// and gain.
nlohmann::json shot_report(const EnvironmentSpec& env, const EnvironmentInfo& info, int face);

}  // namespace insitu
