// The resident memory's peak above where it stood, for a benchmark's one step (Linux): glibc's
// malloc_trim returns the setup's free memory, /proc/self/clear_refs resets VmHWM to the current
// resident set, and VmHWM afterwards is the step's peak.
#pragma once
#include <malloc.h>

#include <fstream>
#include <string>

namespace insitu::bench {

// kB of a /proc/self/status field ("VmHWM", "VmRSS"), −1 when unreadable.
inline long status_kb(const std::string& field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(field + ":", 0) == 0) return std::stol(line.substr(field.size() + 1));
  return -1;
}

class PeakMemory {
 public:
  PeakMemory() {
    malloc_trim(0);
    std::ofstream("/proc/self/clear_refs") << "5";
    before_kb_ = status_kb("VmRSS");
  }
  double peak_mb() const { return double(status_kb("VmHWM") - before_kb_) / 1024.0; }

 private:
  long before_kb_ = 0;
};

}  // namespace insitu::bench
