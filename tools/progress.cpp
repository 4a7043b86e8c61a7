#include "progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fmt/format.h>

namespace insitu {
namespace {

int terminal_columns() {
  winsize ws{};
  if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0) return ws.ws_col;
  if (const char* c = std::getenv("COLUMNS"); c && std::atoi(c) > 0) return std::atoi(c);
  return 80;
}

}  // namespace

std::string progress_line(const std::string& label, double fraction, double elapsed_s, const std::string& detail,
                          int columns) {
  const double eta = fraction > 0 ? elapsed_s * (1 - fraction) / fraction : 0;
  const std::string tail = fmt::format(" {:3d}% {:.0f}s, {:.0f}s left{}{}", int(fraction * 100), elapsed_s, eta,
                                       detail.empty() ? "" : ", ", detail);
  const int room = columns - 1 - int(label.size() + tail.size()) - 3;  // " [" and "]"
  const int bar = std::min(30, room);
  std::string line = label;
  if (bar >= 5) {
    const int filled = int(fraction * bar);
    line += " [" + std::string(std::size_t(filled), '#') + std::string(std::size_t(bar - filled), ' ') + "]";
  }
  line += tail;
  if (int(line.size()) > columns - 1) line.resize(std::size_t(std::max(0, columns - 1)));
  return line;
}

Progress::Progress(std::string label)
    : Progress(std::move(label), Sink{stderr, ::isatty(STDERR_FILENO) != 0, 80, 1.0}) {
  if (sink_.tty) sink_.columns = terminal_columns();
}

Progress::Progress(std::string label, Sink sink)
    : label_(std::move(label)), sink_(sink), start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { finish(); }

void Progress::update(double fraction, const std::string& detail, bool milestone) {
  const auto now = std::chrono::steady_clock::now();
  if (fraction == 0.0 && !shown_ && detail.empty()) {
    start_ = now;  // work starts now: earlier set-up is not part of it
    return;
  }
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < sink_.quiet_s || finished_) return;
  if (sink_.tty) {
    if (shown_ && now - last_draw_ < std::chrono::milliseconds(100) && fraction < 1.0) return;
    // \r and "erase to the end of the line": a shorter line leaves nothing of the longer one.
    std::fprintf(sink_.out, "\r%s\x1b[K", progress_line(label_, fraction, elapsed, detail, sink_.columns).c_str());
    last_draw_ = now;
  } else {
    const int decile = int(fraction * 10 + 1e-9);
    if (!milestone || detail.empty() || decile <= last_decile_) return;
    last_decile_ = decile;
    std::fprintf(sink_.out, "%s: %d%% (%.1f s) %s\n", label_.c_str(), int(fraction * 100 + 0.5), elapsed,
                 detail.c_str());
  }
  shown_ = true;
  std::fflush(sink_.out);
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (shown_ && sink_.tty) std::fprintf(sink_.out, "\n");
}

}  // namespace insitu
