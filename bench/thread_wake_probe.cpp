// Whether this machine can show a thread speed-up right now: a oneTBB arena of 2 threads runs
// many short passes, each a parallel loop of `pieces` busy-waits of `piece_us` microseconds
// after `gap_us` of serial work (a detection pass between the caller's position writes), and
// the probe reports how much of the work the second thread took and how late it joined. On two
// free cores the worker takes close to half of every pass; when other processes keep the cores
// busy, it is woken late or not at all, and no 2-thread figure measured then says anything about
// the code (docs/benchmarks.md, "Threads").
//
//   build/release/bench/bench_thread_wake [gap_us=10] [pieces=200] [piece_us=5] [passes=300]

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace {

using Clock = std::chrono::steady_clock;

double micros_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
}

void busy_wait(double us) {
  const Clock::time_point t0 = Clock::now();
  while (micros_since(t0) < us) {
  }
}

}  // namespace

int main(int argc, char** argv) {
  const double gap_us = argc > 1 ? std::atof(argv[1]) : 10.0;
  const int pieces = argc > 2 ? std::atoi(argv[2]) : 200;
  const double piece_us = argc > 3 ? std::atof(argv[3]) : 5.0;
  const int passes = argc > 4 ? std::atoi(argv[4]) : 300;
  tbb::task_arena arena(2);
  long worker_pieces = 0;
  int joined = 0;
  double join_sum_us = 0.0;
  double pass_sum_us = 0.0;
  for (int p = 0; p < passes; ++p) {
    busy_wait(gap_us);
    std::atomic<double> first_join{-1.0};
    std::atomic<long> taken{0};
    const Clock::time_point t0 = Clock::now();
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, pieces, 1),
                        [&](const tbb::blocked_range<int>& r) {
                          for (int i = r.begin(); i != r.end(); ++i) {
                            if (tbb::this_task_arena::current_thread_index() != 0) {
                              double none = -1.0;
                              first_join.compare_exchange_strong(none, micros_since(t0));
                              ++taken;
                            }
                            busy_wait(piece_us);
                          }
                        });
    });
    pass_sum_us += micros_since(t0);
    worker_pieces += taken;
    if (first_join >= 0.0) {
      ++joined;
      join_sum_us += first_join;
    }
  }
  std::printf(
      "%d passes of %d x %.1f us after %.0f us serial: %.1f us a pass (%.1f us of work); the "
      "worker took %.1f %% of the pieces, joined %d passes, %.1f us after the start on "
      "average\n",
      passes, pieces, piece_us, gap_us, pass_sum_us / passes, pieces * piece_us,
      100.0 * static_cast<double>(worker_pieces) / (static_cast<double>(passes) * pieces), joined,
      joined > 0 ? join_sum_us / joined : 0.0);
  return 0;
}
