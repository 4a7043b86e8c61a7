#include "core/file_check.h"

#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace insitu {
namespace fs = std::filesystem;

void require_existing(const std::string& path) {
  std::error_code ec;
  const bool found = fs::exists(path, ec);
  if (ec && ec != std::errc::no_such_file_or_directory) throw InputError(path, "cannot access: " + ec.message());
  if (!found) throw InputError(path, "file not found");
}

bool exists_quietly(const std::string& path) {
  std::error_code ec;
  return fs::exists(path, ec) && !ec;
}

bool is_directory_quietly(const std::string& path) {
  std::error_code ec;
  return fs::is_directory(path, ec) && !ec;
}

}  // namespace insitu
