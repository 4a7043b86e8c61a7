#include "core/staged_writes.h"

#include <filesystem>

#include "core/error.h"
#include "core/file_check.h"

namespace insitu {
namespace fs = std::filesystem;

StagedWrites::~StagedWrites() {
  for (const Staged& s : staged_) {
    std::error_code ignored;
    fs::remove(s.tmp, ignored);
  }
}

void StagedWrites::add(const std::string& tmp, const std::string& path) {
  staged_.push_back({tmp, path, std::make_unique<TempFileGuard>(tmp)});
}

void StagedWrites::commit() {
  for (const Staged& s : staged_)
    if (is_directory_quietly(s.path)) throw InputError(s.path, "is a directory");
  for (Staged& s : staged_) {
    std::error_code ec;
    fs::rename(s.tmp, s.path, ec);
    if (ec) throw InputError(s.path, "cannot write: " + ec.message());
    s.tmp.clear();  // renamed: nothing left to remove
    s.guard.reset();
  }
  staged_.clear();
}

}  // namespace insitu
