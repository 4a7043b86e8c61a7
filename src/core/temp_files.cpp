#include "core/temp_files.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace insitu {
namespace {

constexpr int kSlots = 32;
constexpr std::size_t kPathMax = 4096;
char g_paths[kSlots][kPathMax];
std::atomic<bool> g_claimed[kSlots];  // owned by a guard (its path may be half written)
std::atomic<bool> g_used[kSlots];     // published: the handler may read the path
std::atomic<bool> g_installed{false};
std::atomic<bool> g_graceful{false}, g_stop{false};  // lock-free: safe to touch in a handler
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void remove_temps_and_die(int sig) {
  if ((sig == SIGINT || sig == SIGTERM) && g_graceful.exchange(false)) {
    g_stop.store(true);
    return;
  }
  for (int i = 0; i < kSlots; ++i)
    if (g_used[i].load(std::memory_order_acquire)) ::unlink(g_paths[i]);
  std::signal(sig, SIG_DFL);  // then end as the signal would have (exit status 128 + sig)
  std::raise(sig);
}

}  // namespace

void install_interrupt_cleanup() {
  if (g_installed.exchange(true)) return;
  struct sigaction sa {};
  sa.sa_handler = remove_temps_and_die;
  sigemptyset(&sa.sa_mask);
  // A signal ignored at start stays ignored: nohup's SIGHUP, SIGINT of a shell's background job.
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    sigaction(sig, &sa, nullptr);
  }
}

void arm_graceful_stop(bool armed) { g_graceful.store(armed); }

const std::atomic<bool>& graceful_stop_flag() { return g_stop; }

void remove_stale_temporaries(const std::string& final_path, const std::string& prefix) {
  const std::filesystem::path p(final_path);
  const std::filesystem::path dir = p.parent_path().empty() ? "." : p.parent_path();
  const std::string start = "." + prefix + ".tmp-";
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.compare(0, start.size(), start) != 0) continue;
    char* digits_end = nullptr;
    const long pid = std::strtol(name.c_str() + start.size(), &digits_end, 10);
    if (pid <= 0 || digits_end == name.c_str() + start.size()) continue;
    if (::kill(pid_t(pid), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      std::filesystem::remove(it->path(), ignored);
    }
  }
}

TempFileGuard::TempFileGuard(const std::string& path) {
  if (path.size() >= kPathMax) return;  // not protected; still removed on ordinary failures
  for (int i = 0; i < kSlots; ++i) {
    if (g_claimed[i].exchange(true, std::memory_order_acq_rel)) continue;  // another guard's
    std::memcpy(g_paths[i], path.c_str(), path.size() + 1);
    g_used[i].store(true, std::memory_order_release);  // the path is complete: publish it
    slot_ = i;
    return;
  }
}

TempFileGuard::~TempFileGuard() {
  if (slot_ < 0) return;
  g_used[slot_].store(false, std::memory_order_release);
  g_claimed[slot_].store(false, std::memory_order_release);
}

}  // namespace insitu
