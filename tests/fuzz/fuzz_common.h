// Shared by the libFuzzer targets: the readers take paths, so each input is written to a file in a
// per-process folder first. An input may be refused (InputError: the documented behaviour); any
// other exception, a crash, a hang or a sanitizer report is a finding.
#pragma once
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"

namespace insitu::fuzz {

inline std::string work_dir() {
  static const std::string dir = [] {
    const auto d = std::filesystem::temp_directory_path() / ("insitu-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d.string();
  }();
  return dir;
}

inline std::string write_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::string path = work_dir() + "/" + name;
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

// Runs f(); InputError is a refusal, which is fine; anything else aborts, so libFuzzer keeps it.
template <typename F>
int run(F&& f) {
  try {
    f();
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "not an InputError: %s\n", e.what());
    std::abort();
  }
  return 0;
}

}  // namespace insitu::fuzz
