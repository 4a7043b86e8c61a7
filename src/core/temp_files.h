// Temporary files of outputs being written (write, then rename: no half-written file ever has a
// final name). If the process is interrupted (SIGINT, SIGTERM, SIGHUP) while one exists, the
// handler removes it before the process ends by the signal: no hidden ".x.tmp-PID" is left
// behind. A fixed table of slots, so that the handler only reads plain memory and calls unlink(2),
// which is async-signal-safe.
#pragma once
#include <atomic>
#include <string>

namespace insitu {

// Installs the handlers (once; later calls do nothing). The CLI calls it at start.
void install_interrupt_cleanup();

// A graceful stop: while armed, the first SIGINT or SIGTERM only sets the flag that
// graceful_stop_flag() returns (the render finishes its pass, writes its partial image and a
// checkpoint, and exits 130); the stop disarms itself, so a second signal ends the process as
// before. Disarming leaves a flag that was set as it is.
void arm_graceful_stop(bool armed);
const std::atomic<bool>& graceful_stop_flag();

// The temporaries of an output that a killed process left (SIGKILL cannot be caught): the files
// beside `final_path` named ".<prefix>.tmp-<pid>..." (<prefix> its stem for images, its whole name
// for text files) whose process no longer runs (kill(pid, 0) says ESRCH). A live process's,
// another insitu writing the same name, is left alone. Called before each write of `final_path`.
void remove_stale_temporaries(const std::string& final_path, const std::string& prefix);

// A temporary file for as long as the object lives: registered on construction, unregistered on
// destruction (after the rename, or after a failed write has removed it).
class TempFileGuard {
 public:
  explicit TempFileGuard(const std::string& path);
  ~TempFileGuard();
  TempFileGuard(const TempFileGuard&) = delete;
  TempFileGuard& operator=(const TempFileGuard&) = delete;

 private:
  int slot_ = -1;
};

}  // namespace insitu
