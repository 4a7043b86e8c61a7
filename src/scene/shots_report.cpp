#include "scene/shots_report.h"

namespace insitu {

nlohmann::json registration_json(const std::optional<Registration>& r, int f) {
  if (!r) return nullptr;
  const ShotAim& a = r->shots[std::size_t(f)];
  nlohmann::json j = {{"registered", a.registered},    {"rotation_deg", a.rotation_deg}, {"yaw_deg", a.yaw_deg},
                      {"pitch_deg", a.pitch_deg},      {"roll_deg", a.roll_deg},         {"matches", a.matches},
                      {"residual_deg", a.residual_deg}};
  if (!a.registered) j["reason"] = a.reason;
  return j;
}

nlohmann::json room_lines_json(const std::optional<LineAnchor>& a, int f) {
  if (!a) return nullptr;
  const auto s = std::size_t(f);
  // A shot whose room-box turn was past a hand's misaim is levelled by its plumb lines (off_box).
  nlohmann::json j = {{"axes", a->axes == LineAxes::vertical || a->off_box[s] ? "vertical" : "room"},
                      {"anchored", a->anchored[s]},
                      {"turn_deg", a->turn_deg[s]},
                      {"sigma_deg", a->sigma_deg[s]},
                      {"lines_xyz", a->lines[s]}};
  if (!a->anchored[s] || a->off_box[s]) j["reason"] = a->reason[s];
  if (a->off_box[s]) j["off_box_turn_deg"] = a->off_box_turn_deg[s];
  return j;
}

nlohmann::json photo_anchor_json(const std::optional<PhotoAnchor>& a, int f) {
  if (!a) return nullptr;
  const auto s = std::size_t(f);
  nlohmann::json j = {{"anchored", a->anchored[s]},
                      {"matches", a->matches[s]},
                      {"turn_deg", a->turn_deg[s]},
                      {"residual_deg", a->residual_deg[s]}};
  if (!a->anchored[s]) j["reason"] = a->reason[s];
  return j;
}

nlohmann::json shot_report(const EnvironmentSpec& env, const EnvironmentInfo& info, int f) {
  const auto s = std::size_t(f);
  return {{"face", face_name(f)},
          {"files", env.shots[s].files},
          {"rotate_deg", env.shots[s].rotate_deg},
          {"coverage_percent", 100 * info.coverage[s]},
          {"clipped_percent", 100 * info.clipped[s]},
          {"registration", registration_json(info.registration, f)},
          {"room_lines", room_lines_json(info.line_anchor, f)},
          {"photo_anchor", photo_anchor_json(info.photo_anchor, f)},
          {"gain", {info.shot_gain[s][0], info.shot_gain[s][1], info.shot_gain[s][2]}}};
}

}  // namespace insitu
