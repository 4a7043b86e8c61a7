// Progress for anything that takes over a second.
//
// On a terminal: one line redrawn in place at most 10 times a second, fitted to the terminal's
// width (the bar shrinks first, then the line is cut), so that it never wraps. Elsewhere (a log, a
// pipe): a plain line at each milestone (the end of a pass of samples) that reaches a new tenth of
// the work, carrying the milestone's figures; no line without figures, no line twice. Nothing is
// shown for work that ends within a second.
#pragma once
#include <chrono>
#include <cstdio>
#include <string>

namespace insitu {

// The progress line for a terminal `columns` wide: at most columns − 1 characters.
std::string progress_line(const std::string& label, double fraction, double elapsed_s, const std::string& detail,
                          int columns);

class Progress {
 public:
  struct Sink {
    std::FILE* out = stderr;
    bool tty = false;
    int columns = 80;
    double quiet_s = 1.0;  // nothing is shown before this much time has passed
  };
  explicit Progress(std::string label);  // stderr, as it is (terminal or not, and its width)
  Progress(std::string label, Sink sink);
  ~Progress();
  // `detail` (e.g. "64/144 spp, noise 3.1%") describes the work up to the last milestone;
  // `milestone` marks the call that reaches one. Not thread-safe: callers serialize.
  void update(double fraction, const std::string& detail = "", bool milestone = false);
  void finish();

 private:
  std::string label_;
  Sink sink_;
  bool shown_ = false;
  bool finished_ = false;
  int last_decile_ = 0;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace insitu
