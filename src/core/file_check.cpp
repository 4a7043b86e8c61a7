#include "core/file_check.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
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

std::string sync_to_disk(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::string("cannot open it again: ") + std::strerror(errno);
  const bool synced = ::fsync(fd) == 0;
  const int sync_errno = errno;
  ::close(fd);
  return synced ? "" : std::string("cannot flush it to the disk: ") + std::strerror(sync_errno);
}

}  // namespace insitu
