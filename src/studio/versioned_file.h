// A file the studio edits on the page's behalf (points.json, the scene file), safe against two
// tabs or another program.
//
// Every read returns the file's text with a version: the FNV-1a hash of its bytes. An update
// names the version it was edited from. If the file has changed since, the update is refused as a
// conflict and nothing is written; otherwise the edit is applied to the current text and written
// atomically (write, then rename). Updates are serialized, so two tabs can never interleave their
// writes: the first wins, the second hears of the conflict.
#pragma once
#include <functional>
#include <mutex>
#include <string>

namespace insitu {

struct FileVersion {
  std::string text;     // the file's bytes (`if_missing` when it does not exist yet)
  std::string version;  // 16 hex digits
};

class VersionedFile {
 public:
  VersionedFile(std::string path, std::string if_missing)
      : path_(std::move(path)), if_missing_(std::move(if_missing)) {}
  const std::string& path() const { return path_; }

  FileVersion read() const;
  // The outcome of an update: saved (with the new version), or a conflict (with the file as it is).
  struct UpdateResult {
    bool saved = false;
    FileVersion now;
  };
  // `edit` maps the current text to the new one; what it throws propagates and nothing is written.
  UpdateResult update(const std::string& edited_from_version,
                      const std::function<std::string(const std::string&)>& edit);

 private:
  FileVersion read_unlocked() const;
  std::string path_, if_missing_;
  mutable std::mutex mutex_;
};

}  // namespace insitu
