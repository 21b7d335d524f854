#include "gpu/gl/fault_injection.h"

#include <array>
#include <atomic>
#include <cstddef>

namespace deformcd::gl::fault {

namespace {

// Operation n (1-based, counted in `done`) fails when from <= n < until; from = 0: disarmed.
struct Counter {
  std::atomic<std::uint64_t> done{0};
  std::atomic<std::uint64_t> from{0};
  std::atomic<std::uint64_t> until{0};
};

std::array<Counter, 3> counters;

Counter& counter(Kind kind) {
  return counters[static_cast<std::size_t>(kind)];
}

}  // namespace

void arm(Kind kind, std::uint64_t first, std::uint64_t count) {
  Counter& c = counter(kind);
  const std::uint64_t from = c.done.load() + (first == 0 ? 1 : first);
  c.until.store(count > kForever - from ? kForever : from + count);
  c.from.store(from);
}

void disarm(Kind kind) {
  counter(kind).from.store(0);
}

std::uint64_t operations(Kind kind) {
  return counter(kind).done.load();
}

bool should_fail(Kind kind) {
  Counter& c = counter(kind);
  const std::uint64_t n = c.done.fetch_add(1) + 1;
  const std::uint64_t from = c.from.load(std::memory_order_relaxed);
  return from != 0 && n >= from && n < c.until.load(std::memory_order_relaxed);
}

}  // namespace deformcd::gl::fault
