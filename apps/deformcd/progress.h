#pragma once
// What a long command shows while it works, on stderr: status lines as it starts ("reading the
// scene", "building 2 bodies"), then a progress bar with the elapsed time, the rate and the
// time left. On a terminal the bar is redrawn in place; otherwise (a log, a pipe) a plain line
// is written every few seconds instead.

#include <chrono>
#include <cstdio>
#include <string>

namespace deformcd::app {

/// One status line on stderr ("deformcd: <text>"), at once.
void status(const std::string& text);

/// "0:07", "1:05", "1:02:09".
[[nodiscard]] std::string format_duration(double seconds);

/// "12/450 frames | 0:03 | 3.8 frames/s | 1:55 left" (the rate as "2.5 s/frame" below one a
/// second; no rate or time left before the first unit is done or the first second is over).
[[nodiscard]] std::string progress_counts(long done, long total, const std::string& unit,
                                          double elapsed_s);

class Progress {
 public:
  using Clock = std::chrono::steady_clock;

  /// Where and how the progress is shown.
  struct Output {
    std::FILE* stream = stderr;
    bool terminal = false;         ///< redraw one line in place, else write periodic lines
    double line_interval_s = 5.0;  ///< seconds between the lines when not a terminal
  };
  /// On stderr, as a bar when stderr is a terminal.
  Progress(std::string label, long total, std::string unit = "frames");
  Progress(std::string label, long total, std::string unit, Output output,
           Clock::time_point start = Clock::now());
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// What is being done, shown before the bar (e.g. the method being measured).
  void set_label(const std::string& label) { label_ = label; }
  /// Reports `done` of `total` units; redraws at most ~10 times a second.
  void update(long done) { update(done, Clock::now()); }
  void update(long done, Clock::time_point now);
  /// Clears the bar from the terminal line so that another line can be printed; the next update
  /// draws it again.
  void clear();
  /// Clears the bar (terminal), or writes a last line when lines were written (not a terminal).
  void done() { done(Clock::now()); }
  void done(Clock::time_point now);

 private:
  [[nodiscard]] double seconds_since_start(Clock::time_point now) const;

  std::string label_;
  long total_;
  std::string unit_;
  Output out_;
  Clock::time_point start_;
  Clock::time_point last_{};
  long done_ = 0;
  bool shown_ = false;    // a bar is on the terminal line
  bool written_ = false;  // a periodic line was written
  bool finished_ = false;
};

}  // namespace deformcd::app
