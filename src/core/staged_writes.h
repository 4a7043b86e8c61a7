// Outputs that land together (a render's image, layers and report). Each file is
// written under its temporary name, flushed and verified as alone (image.h, text_file.h), but not
// renamed: commit() renames them all, in the order written, once every one has been written.
// If a write fails, or commit() is never reached, the destructor removes every temporary, so no
// final file has changed: never new layers beside an old image and report.
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/temp_files.h"

namespace insitu {

class StagedWrites {
 public:
  StagedWrites() = default;
  StagedWrites(const StagedWrites&) = delete;
  StagedWrites& operator=(const StagedWrites&) = delete;
  ~StagedWrites();

  // A temporary file, verified, whose final name is `path` (the writers call it).
  void add(const std::string& tmp, const std::string& path);
  // Renames every temporary to its final name; throws InputError naming the first final name that
  // cannot take it (a folder in its place), before any is renamed.
  void commit();

 private:
  struct Staged {
    std::string tmp, path;
    std::unique_ptr<TempFileGuard> guard;  // removed on SIGINT until renamed
  };
  std::vector<Staged> staged_;
};

}  // namespace insitu
