// Running the insitu binary from tests: stdin closed, stdout and stderr captured.
#pragma once
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "test_util.h"

namespace insitu::test {

struct CliRun {
  int exit_code;
  std::string out, err;
};

// Runs the insitu binary with `args`, stdin closed, capturing stdout and stderr.
inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Under the sanitizer leg, the insitu processes the tests start take full stacks at every
// allocation, so that tests/sanitizer/lsan.supp can name a third-party frame (these runs are short;
// the in-process tests keep the fast unwinder).
inline std::string child_environment() {
  const char* asan = std::getenv("ASAN_OPTIONS");
  return asan && *asan ? "ASAN_OPTIONS='" + std::string(asan) + ":fast_unwind_on_malloc=0' " : "";
}

// Runs the insitu binary with `args`, stdin closed, capturing stdout and stderr.
inline CliRun run_insitu(const TempDir& dir, const std::string& args) {
  const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
  const std::string cmd = child_environment() + INSITU_BINARY + " " + args + " < /dev/null > " + out + " 2> " + err;
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

inline int count_lines(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

inline void expect_one_line_error(const CliRun& r, const std::string& contains) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("insitu: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(contains), std::string::npos) << r.err;
}


}  // namespace insitu::test
