#include "text_file.h"

#include <unistd.h>

#include <filesystem>
#include <fmt/format.h>
#include <fstream>

#include "error.h"

namespace insitu {
namespace fs = std::filesystem;

void write_text_file(const std::string& path, const std::string& text) {
  const fs::path p(path);
  std::error_code ec;
  if (!p.parent_path().empty()) fs::create_directories(p.parent_path(), ec);
  const fs::path tmp = p.parent_path() / fmt::format(".{}.tmp-{}", p.filename().string(), ::getpid());
  {
    std::ofstream out(tmp);
    out << text;
    out.close();
    if (!out) {
      fs::remove(tmp, ec);
      throw InputError(path, "cannot write");
    }
  }
  fs::rename(tmp, p, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError(path, "cannot write: " + ec.message());
  }
}

}  // namespace insitu
