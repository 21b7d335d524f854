// parallel_select: the indices a predicate keeps, in order, the same on any number of threads.

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "cpu/executor.h"
#include "cpu/parallel_for.h"

namespace deformcd::cpu {
namespace {

// A predicate with runs and gaps of every length up to a few hundred (a hash of the index).
bool kept(std::size_t i) {
  std::uint64_t h = i * 0x9E3779B97F4A7C15ull;
  h ^= h >> 29;
  return (h & 3u) != 0u && (i / 300u) % 3u != 1u;
}

std::vector<std::uint32_t> serial(std::size_t count) {
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < count; ++i)
    if (kept(i)) out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

TEST(ParallelSelect, KeepsTheSerialFiltersListOnOneTwoAndEightThreads) {
  constexpr std::size_t kBlock = 64;
  // Empty, within one block, at and across block ends, and many blocks.
  for (const std::size_t count : {0, 1, 63, 64, 65, 1000, 10 * 64, 50'001}) {
    const std::vector<std::uint32_t> expected = serial(count);
    for (const int threads : {1, 2, 8}) {
      Executor executor(threads);
      std::vector<std::uint32_t> out = {7u, 7u, 7u};  // stale entries must go
      std::vector<std::uint32_t> starts;
      executor.run([&] { parallel_select(count, kept, out, starts, kBlock); });
      EXPECT_EQ(out, expected) << count << " indices, " << threads << " threads";
    }
  }
}

TEST(ParallelSelect, KeepsNoneAndAll) {
  Executor executor(2);
  std::vector<std::uint32_t> out, starts;
  executor.run([&] {
    parallel_select(
        5000, [](std::size_t) { return false; }, out, starts, 128);
  });
  EXPECT_TRUE(out.empty());
  executor.run([&] {
    parallel_select(
        5000, [](std::size_t) { return true; }, out, starts, 128);
  });
  ASSERT_EQ(out.size(), 5000u);
  for (std::uint32_t i = 0; i < out.size(); ++i)
    ASSERT_EQ(out[i], i);
}

}  // namespace
}  // namespace deformcd::cpu
