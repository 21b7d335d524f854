// The progress display: status, elapsed time, rate and time left; a bar redrawn in place on a
// terminal, periodic plain lines elsewhere.

#include "apps/deformcd/progress.h"

#include <chrono>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

namespace deformcd::app {
namespace {

using std::chrono::seconds;

// What was written to a temporary stream.
std::string contents(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string text;
  for (int c; (c = std::fgetc(f)) != EOF;)
    text.push_back(static_cast<char>(c));
  return text;
}

TEST(Progress, DurationsReadAsClockTimes) {
  EXPECT_EQ(format_duration(0.0), "0:00");
  EXPECT_EQ(format_duration(7.4), "0:07");
  EXPECT_EQ(format_duration(65.0), "1:05");
  EXPECT_EQ(format_duration(3729.0), "1:02:09");
}

TEST(Progress, CountsGiveTheElapsedTimeTheRateAndTheTimeLeft) {
  EXPECT_EQ(progress_counts(0, 450, "frames", 2.0), "0/450 frames | 0:02");
  EXPECT_EQ(progress_counts(30, 450, "frames", 0.2), "30/450 frames | 0:00");  // too early
  EXPECT_EQ(progress_counts(12, 450, "frames", 3.0),
            "12/450 frames | 0:03 | 4.0 frames/s | 1:50 left");  // 438 / 4 = 109.5 s
  // Below one a second, the time per unit.
  EXPECT_EQ(progress_counts(2, 60, "frames", 5.0), "2/60 frames | 0:05 | 2.5 s/frame | 2:25 left");
  EXPECT_EQ(progress_counts(60, 60, "frames", 30.0), "60/60 frames | 0:30 | 2.0 frames/s");
}

TEST(Progress, OffATerminalItWritesAPlainLineEveryFewSecondsAndALastOne) {
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  const auto t0 = Progress::Clock::now();
  {
    Progress p("simulating", 100, "frames", {out, false, 5.0}, t0);
    p.update(1, t0 + seconds(1));
    EXPECT_EQ(contents(out), "");  // nothing for short runs
    p.update(10, t0 + seconds(5));
    p.update(11, t0 + seconds(6));
    p.update(50, t0 + seconds(10));
    p.done(t0 + seconds(20));
  }
  EXPECT_EQ(contents(out),
            "simulating: 10/100 frames | 0:05 | 2.0 frames/s | 0:45 left\n"
            "simulating: 50/100 frames | 0:10 | 5.0 frames/s | 0:10 left\n"
            "simulating: 50/100 frames | 0:20 | 2.5 frames/s | 0:20 left\n");
  std::fclose(out);
}

TEST(Progress, OnATerminalTheBarIsRedrawnInPlaceAndClearedAtTheEnd) {
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  const auto t0 = Progress::Clock::now();
  Progress p("simulating", 4, "frames", {out, true, 5.0}, t0);
  p.update(1, t0 + seconds(1));
  EXPECT_EQ(
      contents(out),
      "\r\033[Ksimulating [#####               ] 1/4 frames | 0:01 | 1.0 frames/s | 0:03 left");
  p.done(t0 + seconds(4));
  const std::string text = contents(out);
  EXPECT_EQ(text.substr(text.size() - 4), "\r\033[K");  // the line cleared for what follows
  EXPECT_EQ(text.find('\n'), std::string::npos);
  std::fclose(out);
}

}  // namespace
}  // namespace deformcd::app
