#pragma once
// A one-line progress display on stderr, shown only when stderr is a terminal.

#include <chrono>
#include <string>

namespace deformcd::app {

class Progress {
 public:
  Progress(std::string label, long total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Reports `done` of `total`; redraws at most ~10 times a second.
  void update(long done);
  /// Clears the line.
  void done();

 private:
  std::string label_;
  long total_;
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace deformcd::app
