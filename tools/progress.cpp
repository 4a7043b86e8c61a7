#include "progress.h"

#include <unistd.h>

#include <cstdio>
#include <fmt/format.h>

namespace insitu {

Progress::Progress(std::string label)
    : label_(std::move(label)), tty_(::isatty(STDERR_FILENO) != 0), start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { finish(); }

void Progress::update(double fraction, const std::string& detail) {
  const auto now = std::chrono::steady_clock::now();
  if (fraction == 0.0 && !shown_ && detail.empty()) {
    start_ = now;  // work starts now: earlier set-up is not part of it
    return;
  }
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < 1.0 || finished_) return;
  if (tty_) {
    if (shown_ && now - last_draw_ < std::chrono::milliseconds(100) && fraction < 1.0) return;
    const int width = 30, filled = int(fraction * width);
    const double eta = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
    std::fprintf(stderr, "\r%s [%s%s] %3d%%  %.1fs elapsed, %.1fs left %s ", label_.c_str(),
                 std::string(std::size_t(filled), '#').c_str(), std::string(std::size_t(width - filled), ' ').c_str(),
                 int(fraction * 100), elapsed, eta, detail.c_str());
    last_draw_ = now;
    shown_ = true;
  } else {
    const int decile = int(fraction * 10);
    if (decile <= last_decile_) return;
    last_decile_ = decile;
    std::fprintf(stderr, "%s: %d%% (%.1f s) %s\n", label_.c_str(), decile * 10, elapsed, detail.c_str());
    shown_ = true;
  }
  std::fflush(stderr);
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (shown_ && tty_) std::fprintf(stderr, "\n");
}

}  // namespace insitu
