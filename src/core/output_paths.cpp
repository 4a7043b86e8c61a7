#include "core/output_paths.h"

#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <system_error>

#include "core/error.h"

namespace insitu {
namespace fs = std::filesystem;

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (auto& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return ext;
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ea, eb, eq;
  if (fs::exists(a, ea) && fs::exists(b, eb)) return fs::equivalent(a, b, eq) && !eq;
  const fs::path ca = fs::weakly_canonical(a, ea), cb = fs::weakly_canonical(b, eb);
  if (ea || eb) return fs::absolute(a).lexically_normal() == fs::absolute(b).lexically_normal();
  return ca == cb;
}

namespace {

void check_writable(const NamedPath& out) {
  const fs::path p(out.path);
  std::error_code ec;
  if (fs::is_directory(p, ec)) throw InputError(out.role + " " + out.path, "is a directory");
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  fs::create_directories(dir, ec);
  if (ec) throw InputError(out.role + " " + out.path, "cannot create its folder: " + ec.message());
  const fs::path probe = dir / fmt::format(".insitu-probe-{}", ::getpid());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0)
    throw InputError(out.role + " " + out.path, fmt::format("its folder is not writable: {}", std::strerror(errno)));
  ::close(fd);
  fs::remove(probe, ec);
}

}  // namespace

void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const NamedPath& out = outputs[i];
    if (out.path.empty()) continue;
    for (const NamedPath& in : inputs)
      if (!in.path.empty() && same_file(out.path, in.path))
        throw InputError(
            out.role + " " + out.path,
            fmt::format("is {} ({}): an output never replaces an input; choose another name", in.role, in.path));
    for (std::size_t j = 0; j < i; ++j)
      if (!outputs[j].path.empty() && same_file(out.path, outputs[j].path))
        throw InputError(out.role + " " + out.path,
                         fmt::format("is also {}: give each output its own name", outputs[j].role));
  }
  for (const NamedPath& out : outputs)
    if (!out.path.empty()) check_writable(out);
}

}  // namespace insitu
