#include "studio/versioned_file.h"

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/fnv1a.h"
#include "core/text_file.h"

namespace insitu {

namespace {

std::string version_of(const std::string& text) {
  Fnv1a h;
  h.bytes(text.data(), text.size());
  return fmt::format("{:016x}", h.digest());
}

}  // namespace

FileVersion VersionedFile::read_unlocked() const {
  std::error_code ec;
  if (!std::filesystem::exists(path_, ec)) return {if_missing_, version_of(if_missing_)};
  std::ifstream in(path_, std::ios::binary);
  if (!in) throw InputError(path_, "cannot read file");
  std::stringstream ss;
  ss << in.rdbuf();
  return {ss.str(), version_of(ss.str())};
}

FileVersion VersionedFile::read() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return read_unlocked();
}

VersionedFile::UpdateResult VersionedFile::update(const std::string& edited_from_version,
                                                  const std::function<std::string(const std::string&)>& edit) {
  const std::lock_guard<std::mutex> lock(mutex_);
  FileVersion now = read_unlocked();
  if (now.version != edited_from_version) return {false, now};
  const std::string text = edit(now.text);
  write_text_file(path_, text);
  return {true, {text, version_of(text)}};
}

}  // namespace insitu
