#pragma once
// The CPU backend's one way of running a loop in parallel (oneTBB), with a grain below which
// work stays on the calling thread. Every element is computed independently of the others and
// written to its own slot, so results do not depend on the thread count or the schedule.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

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

/// The indices i < count for which keep(i) holds, in increasing order, into `out`: blocks of
/// `block` indices counted in parallel, then written in parallel from their prefix sums (`starts`
/// is scratch). The same list on any number of threads.
template <class Keep>
void parallel_select(std::size_t count, const Keep& keep, std::vector<std::uint32_t>& out,
                     std::vector<std::uint32_t>& starts, std::size_t block = kDefaultGrain) {
  const std::size_t blocks = (count + block - 1) / block;
  starts.assign(blocks + 1, 0u);
  parallel_for(
      blocks,
      [&](std::size_t b) {
        std::uint32_t kept = 0;
        for (std::size_t i = b * block; i < std::min(count, (b + 1) * block); ++i)
          kept += keep(i) ? 1u : 0u;
        starts[b + 1] = kept;
      },
      1);
  for (std::size_t b = 0; b < blocks; ++b)
    starts[b + 1] += starts[b];
  out.resize(starts[blocks]);
  parallel_for(
      blocks,
      [&](std::size_t b) {
        std::uint32_t next = starts[b];
        for (std::size_t i = b * block; i < std::min(count, (b + 1) * block); ++i)
          if (keep(i)) out[next++] = static_cast<std::uint32_t>(i);
      },
      1);
}

}  // namespace deformcd::cpu
