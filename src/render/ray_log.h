// A record of the rays an EmbreeScene traces, for measuring the kernel against a bare Embree loop
// over the very same rays (bench/kernel_bench.cpp). Off unless a log is attached
// (EmbreeScene::set_ray_log); attached, every intersect() and transmittance() appends its ray to the
// calling thread's list, in the order that thread traced them (so a replay keeps their coherence).
#pragma once
#include <tbb/enumerable_thread_specific.h>

#include <cstddef>
#include <vector>

namespace insitu {

struct LoggedRay {
  float org[3], dir[3];
  float t_near, t_far;
  bool shadow;  // transmittance() (any hit) rather than intersect() (closest hit)
};

class RayLog {
 public:
  void record(const LoggedRay& ray) { per_thread_.local().push_back(ray); }
  // The lists, one per thread that traced.
  std::vector<std::vector<LoggedRay>> lists() const { return {per_thread_.begin(), per_thread_.end()}; }
  std::size_t size() const {
    std::size_t n = 0;
    for (const auto& list : per_thread_) n += list.size();
    return n;
  }

 private:
  tbb::enumerable_thread_specific<std::vector<LoggedRay>> per_thread_;
};

}  // namespace insitu
