// A request to stop long work before it ends: the studio's Stop, or its Ctrl-C, during loading
// and an integrator's preparation (seconds at 640 × 480, minutes with inverse lighting at a
// catalogue still's size). The work looks at the flag between its stages and in the bodies of its
// parallel loops, often enough that a stop takes effect within a fraction of a second, and throws
// Stopped; the one who asked catches it. Nothing is kept of the work stopped: a cache stores
// only what was finished.
//
// A null flag: nobody can ask (the CLI, whose Ctrl-C during loading ends the process).
#pragma once
#include <atomic>
#include <stdexcept>

namespace insitu {

struct Stopped : std::runtime_error {
  Stopped() : std::runtime_error("stopped before it ended") {}
};

// Throws Stopped when the flag is set. From a TBB loop's body, TBB ends the loop and rethrows it
// in the thread that started the loop.
inline void throw_if_stopped(const std::atomic<bool>* stop) {
  if (stop && stop->load(std::memory_order_relaxed)) throw Stopped();
}

}  // namespace insitu
