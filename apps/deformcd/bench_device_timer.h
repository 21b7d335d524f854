#pragma once
// The device time of `deformcd bench`'s two stages (simulation, collision detection) on GL, from
// timer queries (GL_TIME_ELAPSED, deformcd/gl/timer_query.h), beside the wall clock. The
// queries bracket each stage; their results are read after the stage's wall clock has stopped
// (the world has waited for the device by then, so the read waits for nothing). Built from
// bench_device_timer_gl.cpp, or bench_device_timer_none.cpp (measures nothing) without GL.

#include <array>
#include <memory>
#include <optional>

namespace deformcd::app {

enum class BenchStage { kSimulation = 0, kCollision = 1 };

class StageDeviceTimer {
 public:
  /// `gl`: the world runs on GL and its context is current; otherwise nothing is measured.
  explicit StageDeviceTimer(bool gl);
  ~StageDeviceTimer();
  StageDeviceTimer(const StageDeviceTimer&) = delete;
  StageDeviceTimer& operator=(const StageDeviceTimer&) = delete;

  void begin(BenchStage stage);
  void end(BenchStage stage);
  /// The device seconds of the stage's last begin()/end(); nullopt when nothing is measured.
  [[nodiscard]] std::optional<double> seconds(BenchStage stage) const;

 private:
  struct Queries;
  std::unique_ptr<Queries> queries_;
};

}  // namespace deformcd::app
