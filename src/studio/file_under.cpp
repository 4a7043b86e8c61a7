#include "studio/file_under.h"

#include <algorithm>

namespace insitu {
namespace fs = std::filesystem;

namespace {

// Refused from the text alone: empty, NUL, backslash, absolute, or a ".." component.
bool lexically_allowed(const std::string& relative) {
  if (relative.empty() || relative.find('\0') != std::string::npos || relative.find('\\') != std::string::npos)
    return false;
  const fs::path rel(relative);
  if (rel.is_absolute() || rel.has_root_name()) return false;
  return std::none_of(rel.begin(), rel.end(), [](const fs::path& part) { return part == ".."; });
}

// Whether `inner` is `outer` or lies below it, component by component (so "/a/bc" is not under "/a/b").
bool is_under(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i)
    if (i == inner.end() || *i != *o) return false;
  return true;
}

}  // namespace

std::optional<fs::path> file_under(const fs::path& folder, const std::string& relative) {
  if (!lexically_allowed(relative)) return std::nullopt;
  std::error_code ec;
  const fs::path root = fs::canonical(folder, ec);
  if (ec) return std::nullopt;
  const fs::path file = fs::canonical(root / relative, ec);
  if (ec || !is_under(file, root) || !fs::is_regular_file(file, ec)) return std::nullopt;
  return file;
}

}  // namespace insitu
