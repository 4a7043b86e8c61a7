// Temporary files of outputs being written (write, then rename: no half-written file ever has a
// final name). If the process is interrupted (SIGINT, SIGTERM, SIGHUP) while one exists, the
// handler removes it before the process ends by the signal: no hidden ".x.tmp-PID" is left
// behind. A fixed table of slots, so that the handler only reads plain memory and calls unlink(2),
// which is async-signal-safe.
#pragma once
#include <string>

namespace insitu {

// Installs the handlers (once; later calls do nothing). The CLI calls it at start.
void install_interrupt_cleanup();

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
