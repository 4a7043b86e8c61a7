#include "studio/points_store.h"

#include "calib/control_points.h"

namespace insitu {

VersionedFile::UpdateResult PointsStore::save(const json& points, const std::string& edited_from_version) {
  control_points_from_json(points, path());  // refuses what the CLI would refuse, before any write
  const std::string text = points.dump(2) + "\n";
  return file_.update(edited_from_version, [&](const std::string&) { return text; });
}

}  // namespace insitu
