#include "studio/scene_edit.h"

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/json_reader.h"

namespace insitu {

namespace {

using ordered = nlohmann::ordered_json;

// The scene's environment.shots, after the reader's own checks (duplicate keys, syntax).
ordered parse(const std::string& text, const std::string& file) {
  parse_json_text(text, file);
  return ordered::parse(text);
}

ordered& shots_of(ordered& scene, const std::string& file) {
  if (!scene.is_object() || !scene.contains("environment") || !scene["environment"].is_object() ||
      !scene["environment"].contains("shots") || !scene["environment"]["shots"].is_object())
    throw InputError(file + ":$.environment", "this scene has no six shots (an HDR image, or none)");
  return scene["environment"]["shots"];
}

ordered& shot_at(ordered& shots, const std::string& file, const std::string& key) {
  if (key == "faced" || key == "front_axis" || key == "hfov_deg" || !shots.contains(key))
    throw InputError(file + ":$.environment.shots", "no shot '" + key + "'");
  return shots[key];
}

std::string dumped(const ordered& scene) { return scene.dump(2) + "\n"; }

}  // namespace

std::string swap_shots(const std::string& text, const std::string& file, const std::string& key_a,
                       const std::string& key_b) {
  ordered scene = parse(text, file);
  ordered& shots = shots_of(scene, file);
  std::swap(shot_at(shots, file, key_a), shot_at(shots, file, key_b));
  return dumped(scene);
}

std::string turn_shot(const std::string& text, const std::string& file, const std::string& key, int by_deg) {
  if (by_deg % 90 != 0) throw InputError(file + ":$.environment.shots." + key, "shots turn by quarter turns");
  ordered scene = parse(text, file);
  ordered& shot = shot_at(shots_of(scene, file), file, key);
  if (shot.is_string())
    shot = ordered{{"file", shot}};
  else if (shot.is_array())
    shot = ordered{{"files", shot}};
  const int before =
      shot.contains("rotate_deg") && shot["rotate_deg"].is_number_integer() ? shot["rotate_deg"].get<int>() : 0;
  const int after = ((before + by_deg) % 360 + 360) % 360;
  if (after == 0)
    shot.erase("rotate_deg");
  else
    shot["rotate_deg"] = after;
  return dumped(scene);
}

std::string set_faced_wall(const std::string& text, const std::string& file, const std::string& wall) {
  if (wall != "+x" && wall != "-x" && wall != "+z" && wall != "-z")
    throw InputError(file + ":$.environment.shots.faced", "the faced wall is one of +x, -x, +z, -z");
  ordered scene = parse(text, file);
  shots_of(scene, file)["faced"] = wall;
  return dumped(scene);
}

std::string add_reference(const std::string& text, const std::string& file, const nlohmann::json& reference) {
  ordered scene = parse(text, file);
  if (!scene.is_object()) throw InputError(file, "the scene is not a JSON object");
  if (!scene.contains("references")) scene["references"] = ordered::array();
  if (!scene["references"].is_array()) throw InputError(file + ":$.references", "expected an array of references");
  ordered item = ordered::object();
  item["polygon_px"] = reference.value("polygon_px", nlohmann::json());
  item["albedo"] = reference.value("albedo", nlohmann::json());
  scene["references"].push_back(item);
  return dumped(scene);
}

std::string remove_reference(const std::string& text, const std::string& file, int index) {
  ordered scene = parse(text, file);
  if (!scene.is_object() || !scene.contains("references") || !scene["references"].is_array() || index < 0 ||
      std::size_t(index) >= scene["references"].size())
    throw InputError(file + ":$.references", "no reference " + std::to_string(index));
  scene["references"].erase(std::size_t(index));
  if (scene["references"].empty()) scene.erase("references");
  return dumped(scene);
}

}  // namespace insitu
