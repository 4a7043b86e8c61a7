// The scene's points.json as the studio reads and saves it (issue 18, "Points" and "Safety").
//
// Every read returns the file's text with a version: the FNV-1a hash of its bytes. A save names
// the version it was edited from. If the file has changed since (another tab, an editor, the
// CLI), the save is refused as a conflict and nothing is written; otherwise the new points are
// checked exactly as the CLI reads them (control_points_from_json: a bad point is refused with
// its JSON path) and written atomically (write, then rename). Saves are serialized, so two tabs
// can never interleave their writes: the first wins, the second hears of the conflict.
#pragma once
#include <mutex>
#include <string>

#include "core/json_reader.h"

namespace insitu {

struct PointsVersion {
  std::string text;     // the file's bytes ("[]" when the file does not exist yet)
  std::string version;  // 16 hex digits
};

class PointsStore {
 public:
  explicit PointsStore(std::string path) : path_(std::move(path)) {}
  const std::string& path() const { return path_; }

  PointsVersion read() const;
  // The outcome of a save: saved (with the new version), or a conflict (with the file as it is).
  struct SaveResult {
    bool saved = false;
    PointsVersion now;
  };
  // Throws InputError (naming points.json and the JSON path) when `points` is not a valid list.
  SaveResult save(const json& points, const std::string& edited_from_version);

 private:
  std::string path_;
  mutable std::mutex mutex_;
};

}  // namespace insitu
