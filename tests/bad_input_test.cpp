// The bad-input matrix (tests/bad_input/, written by make_cases.py): every case runs insitu in a
// temporary folder holding _base/ and the case's files, and must exit with its code, print exactly
// one line on stderr ("insitu: error: ..." matching its regex), leave every file that was there
// byte-for-byte unchanged, and create no file (an empty output folder may remain).
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>

#include "cli_util.h"

namespace insitu {
namespace {

namespace fs = std::filesystem;
const fs::path kMatrix = fs::path(INSITU_SOURCE_DIR) / "tests" / "bad_input";

std::vector<std::string> case_names() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(kMatrix))
    if (fs::is_regular_file(e.path() / "case.json")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Every regular file under dir (not following symlinks) with its content.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it)
    if (it->is_regular_file() && !it->is_symlink())
      files[fs::relative(it->path(), dir).string()] = test::slurp(it->path().string());
  return files;
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// The generated families (make_cases.py: wrong_type_NN_…, bad_number_NN_…, unknown_key_NN_…, one
// scene-file key after another) take one path through the scene parser. Under AddressSanitizer each
// family runs its first case only: fuzz_scene runs that parser there with thousands of inputs, and
// each insitu process costs 1.5 s of CPU (280 shared libraries to load, 0.5 s in the release build),
// 80 s of the sanitizer leg for the 53 others. The release suite runs every case.
bool repeats_a_family(const std::string& name) {
  static const std::regex family("^(wrong_type|bad_number|unknown_key)_([0-9]+)_");
  std::smatch m;
  return std::regex_search(name, m, family) && std::stoi(m[2]) > 0;
}

class BadInput : public testing::TestWithParam<std::string> {};

TEST_P(BadInput, OneLineExitCodeAndNothingTouched) {
  if (test::kUnderAsan && repeats_a_family(GetParam()))
    GTEST_SKIP() << "its family's first case runs under the sanitizers, the parser is fuzzed there";
  const fs::path source = kMatrix / GetParam();
  const nlohmann::json spec = nlohmann::json::parse(test::slurp((source / "case.json").string()));
  test::TempDir tmp;
  const fs::path work = tmp.path() / "case";
  fs::create_directories(work);
  const auto options =
      fs::copy_options::recursive | fs::copy_options::copy_symlinks | fs::copy_options::overwrite_existing;
  fs::copy(kMatrix / "_base", work, options);
  fs::copy(source, work, options);
  fs::remove(work / "case.json");
  const auto before = snapshot(work);
  for (const auto& f : spec["unchanged"]) ASSERT_TRUE(before.count(f.get<std::string>())) << f;

  std::string args;
  for (const auto& a : spec["args"]) args += " " + shell_quote(a.get<std::string>());
  const std::string out = tmp.file("stdout.txt"), err = tmp.file("stderr.txt");
  // INSITU_TEST_BINARY runs the matrix against another build (e.g. an older one, to see which
  // cases it fails).
  const char* other = std::getenv("INSITU_TEST_BINARY");
  const std::string binary = other && *other ? other : INSITU_BINARY;
  const int status = test::run_with_leak_check("cd " + shell_quote(work.string()) + " && ",
                                               binary + args + " < /dev/null > " + out + " 2> " + err, err);
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  const std::string stderr_text = test::slurp(err);

  EXPECT_EQ(code, spec["exit"].get<int>()) << stderr_text;
  EXPECT_EQ(test::count_lines(stderr_text), 1) << stderr_text;
  EXPECT_EQ(stderr_text.rfind("insitu: error: ", 0), 0u) << stderr_text;
  EXPECT_TRUE(std::regex_search(stderr_text, std::regex(spec["message"].get<std::string>()))) << stderr_text;
  const auto after = snapshot(work);
  for (const auto& [name, content] : before) {
    ASSERT_TRUE(after.count(name)) << name << " was removed";
    EXPECT_TRUE(after.at(name) == content) << name << " was changed";
  }
  for (const auto& [name, content] : after) EXPECT_TRUE(before.count(name)) << name << " was created";
}

INSTANTIATE_TEST_SUITE_P(Matrix, BadInput, testing::ValuesIn(case_names()),
                         [](const testing::TestParamInfo<std::string>& param_info) {
                           std::string n = param_info.param;
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

}  // namespace
}  // namespace insitu
