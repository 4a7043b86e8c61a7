// Helpers shared by the tests: where the data lives, temporary folders, and a skip for tests
// that need ../shared/data.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

// Under AddressSanitizer (the sanitizer leg of CI) a few heavy tests shrink their inputs: the
// memory checks need the code paths, not the sizes whose physics the release build checks.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define INSITU_UNDER_ASAN 1
#endif
#endif

namespace insitu::test {

#ifdef INSITU_UNDER_ASAN
constexpr bool kUnderAsan = true;
#else
constexpr bool kUnderAsan = false;
#endif

namespace fs = std::filesystem;

inline std::string test_data(const std::string& name) { return std::string(INSITU_TEST_DATA) + "/" + name; }
inline std::string source_dir() { return INSITU_SOURCE_DIR; }

// ../shared/data beside the repository, or "" when it is absent.
inline std::string shared_data() {
  const fs::path p = fs::path(INSITU_SHARED_DIR) / "data";
  return fs::is_directory(p) ? p.string() : std::string();
}

#define INSITU_REQUIRE_SHARED()                                                                \
  do {                                                                                         \
    if (::insitu::test::shared_data().empty())                                                 \
      GTEST_SKIP() << "../shared/data is absent: this test needs the shared HDRIs and meshes"; \
  } while (0)

// A fresh temporary folder, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            (std::string("insitu-") + (info ? std::string(info->test_suite_name()) + "-" + info->name() : "t") + "-" +
             std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = path_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }

 private:
  fs::path path_;
};

}  // namespace insitu::test
