#include "progress.h"

#include <unistd.h>
#include <cstdio>

namespace deformcd::app {

Progress::Progress(std::string label, long total)
    : label_(std::move(label)), total_(total > 0 ? total : 1), enabled_(isatty(STDERR_FILENO)) {}

Progress::~Progress() {
  done();
}

void Progress::update(long done_count) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (shown_ && done_count < total_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  shown_ = true;
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(kWidth * done_count / total_);
  std::fprintf(stderr, "\r%s [%.*s%*s] %ld/%ld", label_.c_str(), filled,
               "##############################", kWidth - filled, "", done_count, total_);
  std::fflush(stderr);
}

void Progress::done() {
  if (!shown_) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace deformcd::app
