// Running the insitu binary from tests: stdin closed, stdout and stderr captured.
#pragma once
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "test_util.h"

extern char** environ;

namespace insitu::test {

struct CliRun {
  int exit_code;
  std::string out, err;
};

// A file's contents ("" when it cannot be read).
inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The environment of the insitu processes the tests start: under the sanitizer leg, ASAN_OPTIONS,
// with full stacks at every allocation when `full_stacks` (see run_with_leak_check).
inline std::string child_environment(bool full_stacks = false) {
  const char* asan = std::getenv("ASAN_OPTIONS");
  if (!asan || !*asan) return "";
  return "ASAN_OPTIONS='" + std::string(asan) + (full_stacks ? ":fast_unwind_on_malloc=0" : "") + "' ";
}

// Runs `command` (insitu with its arguments and redirections, stderr to err_file) through the
// shell: its wait status. Under the sanitizer leg, LeakSanitizer's stacks come from the fast
// unwinder, which stops at the first frame without a frame pointer (libstdc++'s, OpenImageIO's),
// so tests/sanitizer/lsan.supp cannot name the third-party frame of a known leak in them. Full
// stacks at every allocation cost up to half of a run's time (LightRecovery.*: 50 % in
// _Unwind_Find_FDE, 65 s a test), so a run that reports a leak is run again with full stacks,
// and that run's verdict stands: a leak of insitu's own is reported again.
inline int run_with_leak_check(const std::string& prefix, const std::string& command, const std::string& err_file) {
  const int status = std::system((prefix + child_environment() + command).c_str());
  if (!kUnderAsan || slurp(err_file).find("ERROR: LeakSanitizer") == std::string::npos) return status;
  return std::system((prefix + child_environment(true) + command).c_str());
}

// Runs the insitu binary with `args`, stdin closed, capturing stdout and stderr.
inline CliRun run_insitu(const TempDir& dir, const std::string& args) {
  const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
  const int status =
      run_with_leak_check("", std::string(INSITU_BINARY) + " " + args + " < /dev/null > " + out + " 2> " + err, err);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

inline int count_lines(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

inline void expect_one_line_error(const CliRun& r, const std::string& contains) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("insitu: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(contains), std::string::npos) << r.err;
}

// `insitu ARGS` in the background, its output to files; returns its pid. SIGINT and SIGTERM
// are set to their defaults in the child, as a terminal's process has them: a test binary started
// as a script's background job (`cmd &`) has SIGINT ignored, the child would inherit that, and
// install_interrupt_cleanup rightly leaves an ignored signal ignored (ctest resets them itself).
inline pid_t spawn_insitu(const TempDir& dir, const std::string& args) {
  const std::string cmd = test::child_environment() + "exec " + INSITU_BINARY + " " + args + " < /dev/null > " +
                          dir.file("bg.out") + " 2> " + dir.file("bg.err");
  const char* argv[] = {"/bin/sh", "-c", cmd.c_str(), nullptr};
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF);
  pid_t pid = 0;
  EXPECT_EQ(posix_spawn(&pid, "/bin/sh", nullptr, &attr, const_cast<char**>(argv), environ), 0);
  posix_spawnattr_destroy(&attr);
  return pid;
}

// Waits for the process: its exit code, or 1000 + the signal that ended it.
inline int wait_for(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
}

}  // namespace insitu::test
