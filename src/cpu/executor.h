#pragma once
// Where the CPU backend's parallel loops run: a oneTBB task arena of a fixed number of threads,
// owned by whoever asked for that number (a World hands one to its simulation and its detector;
// a Detector of its own makes one) and passed to what runs in parallel, instead of a
// process-wide tbb::global_control that would also bind every other arena in the process.

#include <memory>
#include <string>
#include <utility>

#include <tbb/info.h>
#include <tbb/task_arena.h>

namespace deformcd::cpu {

class Executor {
 public:
  /// `threads` = 0 uses every core; otherwise exactly that many (1: the calling thread alone).
  explicit Executor(int threads = 0)
      : threads_(threads > 0 ? threads : tbb::info::default_concurrency()), arena_(threads_) {}

  [[nodiscard]] int threads() const { return threads_; }
  /// "CPU, oneTBB, 2 threads".
  [[nodiscard]] std::string describe() const {
    return "CPU, oneTBB, " + std::to_string(threads_) + " thread" + (threads_ == 1 ? "" : "s");
  }

  /// Runs `work` in the arena: the parallel loops it starts use this executor's threads.
  template <class Work>
  void run(Work&& work) {
    arena_.execute(std::forward<Work>(work));
  }

 private:
  int threads_;
  tbb::task_arena arena_;
};

}  // namespace deformcd::cpu
