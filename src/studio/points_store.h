// The scene's points.json as the studio reads and saves it: a
// VersionedFile (conflicts refused, writes atomic and serialized) whose saves are checked exactly
// as the CLI reads points (control_points_from_json: a bad point is refused with its JSON path)
// before anything is written.
#pragma once
#include <string>

#include "core/json_reader.h"
#include "studio/versioned_file.h"

namespace insitu {

class PointsStore {
 public:
  explicit PointsStore(std::string path) : file_(std::move(path), "[]") {}
  const std::string& path() const { return file_.path(); }

  FileVersion read() const { return file_.read(); }
  // Throws InputError (naming points.json and the JSON path) when `points` is not a valid list.
  VersionedFile::UpdateResult save(const json& points, const std::string& edited_from_version);

 private:
  VersionedFile file_;
};

}  // namespace insitu
