#pragma once
// The CPU backend's one way of running a loop in parallel (oneTBB), with a grain below which
// work stays on the calling thread. Every element is computed independently of the others and
// written to its own slot, so results do not depend on the thread count or the schedule.

#include <cstddef>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace deformcd::cpu {

/// Elements per task; below this the loop runs serially.
inline constexpr std::size_t kDefaultGrain = 2048;

template <class Body>
void parallel_for(std::size_t count, const Body& body, std::size_t grain = kDefaultGrain) {
  if (count <= grain) {
    for (std::size_t i = 0; i < count; ++i)
      body(i);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, grain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        body(i);
                    });
}

}  // namespace deformcd::cpu
