#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "core/image.h"
#include "core/temp_files.h"
#include "core/text_file.h"
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
      {
        const TempFileGuard finished(done);
        std::ofstream(done) << "renamed already, say";
      }
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

// A SIGKILL during a write leaves its temporary (no handler runs): the next write of the same
// output removes it, once its process is gone (issue 46), and leaves a live process's alone.
TEST(TempFiles, AKilledWritersTemporaryIsRemovedByTheNextWrite) {
  test::TempDir dir;
  const pid_t dead = fork();
  if (dead == 0) _exit(0);
  ASSERT_GT(dead, 0);
  waitpid(dead, nullptr, 0);  // its PID now names no process (until reused)
  const std::string image_tmp = dir.file(".c.tmp-" + std::to_string(dead) + "-0.png");
  const std::string report_tmp = dir.file(".c.png.report.json.tmp-" + std::to_string(dead));
  const std::string live_tmp = dir.file(".c.tmp-" + std::to_string(::getpid()) + "-99.png");
  for (const std::string& f : {image_tmp, report_tmp, live_tmp}) std::ofstream(f) << "half";
  write_image(dir.file("c.png"), Image(4, 4, 3, 0.5f));
  write_text_file(dir.file("c.png.report.json"), "{}\n");
  EXPECT_FALSE(std::filesystem::exists(image_tmp));
  EXPECT_FALSE(std::filesystem::exists(report_tmp));
  EXPECT_TRUE(std::filesystem::exists(live_tmp)) << "a live process's temporary was removed";
}

}  // namespace
}  // namespace insitu
