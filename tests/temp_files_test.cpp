#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "core/temp_files.h"
#include "test_util.h"

namespace insitu {
namespace {

// A process interrupted (SIGINT, SIGTERM) while a temporary output exists removes it, and still
// ends by the signal; a temporary file whose guard has ended is not touched.
TEST(TempFiles, InterruptRemovesTemporaryOutputs) {
  for (const int sig : {SIGINT, SIGTERM}) {
    test::TempDir dir;
    const std::string tmp = dir.file(".c.tmp-1-0.png"), done = dir.file(".d.tmp-1-1.png");
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      // The signal as a terminal delivers it: a background job of a script starts with SIGINT
      // ignored, and install_interrupt_cleanup rightly leaves an ignored signal ignored.
      std::signal(sig, SIG_DFL);
      install_interrupt_cleanup();
      { const TempFileGuard finished(done); std::ofstream(done) << "renamed already, say"; }
      const TempFileGuard guard(tmp);
      std::ofstream(tmp) << "half written";
      std::raise(sig);
      _exit(0);  // not reached
    }
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << status;
    EXPECT_FALSE(std::filesystem::exists(tmp)) << "the interrupted write left " << tmp;
    EXPECT_TRUE(std::filesystem::exists(done));
  }
}

}  // namespace
}  // namespace insitu
