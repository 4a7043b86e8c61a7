#include "core/text_file.h"
#include "core/file_check.h"

#include <unistd.h>

#include <filesystem>
#include <fmt/format.h>
#include <fstream>

#include "core/error.h"
#include "core/staged_writes.h"
#include "core/temp_files.h"

namespace insitu {
namespace fs = std::filesystem;

void write_text_file(const std::string& path, const std::string& text, StagedWrites* stage) {
  write_binary_file(path, text, stage);
}

void write_binary_file(const std::string& path, const std::string& text, StagedWrites* stage) {
  const fs::path p(path);
  std::error_code ec;
  if (!p.parent_path().empty()) fs::create_directories(p.parent_path(), ec);
  remove_stale_temporaries(path, p.filename().string());
  const fs::path tmp = p.parent_path() / fmt::format(".{}.tmp-{}", p.filename().string(), ::getpid());
  const TempFileGuard guard(tmp.string());  // removed if the process is interrupted meanwhile
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) {
      fs::remove(tmp, ec);
      throw InputError(path, "cannot write (is its folder writable, and is there room on the disk?)");
    }
  }
  if (const std::string why = sync_to_disk(tmp.string()); !why.empty()) {
    fs::remove(tmp, ec);
    throw InputError(path, "cannot write: " + why);
  }
  if (stage) return stage->add(tmp.string(), path);
  fs::rename(tmp, p, ec);
  if (ec) {
    const std::string why = is_directory_quietly(p.string()) ? "is a directory" : "cannot write: " + ec.message();
    std::error_code ignored;  // the removal's own outcome must not replace the reason
    fs::remove(tmp, ignored);
    throw InputError(path, why);
  }
}

}  // namespace insitu
