#include "progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace deformcd::app {

void status(const std::string& text) {
  std::fprintf(stderr, "deformcd: %s\n", text.c_str());
  std::fflush(stderr);
}

std::string format_duration(double seconds) {
  const long total = std::lround(std::max(0.0, seconds));
  char text[32];
  if (total >= 3600) {
    std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", total / 3600, total / 60 % 60, total % 60);
  } else {
    std::snprintf(text, sizeof text, "%ld:%02ld", total / 60, total % 60);
  }
  return text;
}

std::string progress_counts(long done, long total, const std::string& unit, double elapsed_s) {
  std::string text = std::to_string(done) + "/" + std::to_string(total) + " " + unit + " | " +
                     format_duration(elapsed_s);
  // No rate in the first second: too few frames, or a bar created at the first one.
  if (done <= 0 || elapsed_s < 1.0) return text;
  const double rate = static_cast<double>(done) / elapsed_s;
  char figure[64];
  // "frames" -> "frame" for the per-unit form.
  const std::string one =
      unit.size() > 1 && unit.back() == 's' ? unit.substr(0, unit.size() - 1) : unit;
  if (rate >= 1.0) {
    std::snprintf(figure, sizeof figure, " | %.1f %s/s", rate, unit.c_str());
  } else {
    std::snprintf(figure, sizeof figure, " | %.1f s/%s", 1.0 / rate, one.c_str());
  }
  text += figure;
  if (done < total) {
    text += " | " + format_duration(static_cast<double>(total - done) / rate) + " left";
  }
  return text;
}

Progress::Progress(std::string label, long total, std::string unit)
    : Progress(std::move(label), total, std::move(unit),
               Output{stderr, isatty(STDERR_FILENO) != 0, 5.0}) {}

Progress::Progress(std::string label, long total, std::string unit, Output output,
                   Clock::time_point start)
    : label_(std::move(label)),
      total_(total > 0 ? total : 1),
      unit_(std::move(unit)),
      out_(output),
      start_(start),
      last_(start) {}

Progress::~Progress() {
  done();
}

double Progress::seconds_since_start(Clock::time_point now) const {
  return std::chrono::duration<double>(now - start_).count();
}

void Progress::update(long done_count, Clock::time_point now) {
  if (finished_) return;
  done_ = done_count;
  const double elapsed = seconds_since_start(now);
  if (!out_.terminal) {
    if (std::chrono::duration<double>(now - last_).count() < out_.line_interval_s) return;
    last_ = now;
    written_ = true;
    std::fprintf(out_.stream, "%s: %s\n", label_.c_str(),
                 progress_counts(done_count, total_, unit_, elapsed).c_str());
    std::fflush(out_.stream);
    return;
  }
  if (shown_ && done_count < total_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  shown_ = true;
  constexpr int kWidth = 20;
  const int filled = static_cast<int>(kWidth * std::min(done_count, total_) / total_);
  std::fprintf(out_.stream, "\r\033[K%s [%.*s%*s] %s", label_.c_str(), filled,
               "####################", kWidth - filled, "",
               progress_counts(done_count, total_, unit_, elapsed).c_str());
  std::fflush(out_.stream);
}

void Progress::clear() {
  if (!shown_) return;
  std::fprintf(out_.stream, "\r\033[K");
  std::fflush(out_.stream);
  shown_ = false;
}

void Progress::done(Clock::time_point now) {
  if (finished_) return;
  finished_ = true;
  clear();
  if (written_) {
    std::fprintf(out_.stream, "%s: %s\n", label_.c_str(),
                 progress_counts(done_, total_, unit_, seconds_since_start(now)).c_str());
    std::fflush(out_.stream);
  }
}

}  // namespace deformcd::app
