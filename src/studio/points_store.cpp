#include "studio/points_store.h"

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "calib/control_points.h"
#include "core/fnv1a.h"
#include "core/text_file.h"

namespace insitu {

namespace {

std::string version_of(const std::string& text) {
  Fnv1a h;
  h.bytes(text.data(), text.size());
  return fmt::format("{:016x}", h.digest());
}

PointsVersion read_unlocked(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return {"[]", version_of("[]")};
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot read file");
  std::stringstream ss;
  ss << in.rdbuf();
  return {ss.str(), version_of(ss.str())};
}

}  // namespace

PointsVersion PointsStore::read() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return read_unlocked(path_);
}

PointsStore::SaveResult PointsStore::save(const json& points, const std::string& edited_from_version) {
  control_points_from_json(points, path_);  // refuses what the CLI would refuse, before any write
  const std::lock_guard<std::mutex> lock(mutex_);
  PointsVersion now = read_unlocked(path_);
  if (now.version != edited_from_version) return {false, now};
  const std::string text = points.dump(2) + "\n";
  write_text_file(path_, text);
  return {true, {text, version_of(text)}};
}

}  // namespace insitu
