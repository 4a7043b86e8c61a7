// Progress for anything that takes over a second: a bar redrawn in place on a terminal, plain
// lines (every 10%) when stderr is not a terminal. Nothing is shown for work that ends sooner.
#pragma once
#include <chrono>
#include <string>

namespace insitu {

class Progress {
 public:
  explicit Progress(std::string label);
  ~Progress();
  void update(double fraction, const std::string& detail = "");  // not thread-safe: callers serialize
  void finish();

 private:
  std::string label_;
  bool tty_;
  bool shown_ = false;
  bool finished_ = false;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace insitu
