#include <array>

#include "bench_device_timer.h"
#include "deformcd/gl/timer_query.h"

namespace deformcd::app {

struct StageDeviceTimer::Queries {
  std::array<gl::TimerQuery, 2> stage;
};

StageDeviceTimer::StageDeviceTimer(bool gl) {
  if (gl) queries_ = std::make_unique<Queries>();
}

StageDeviceTimer::~StageDeviceTimer() = default;

void StageDeviceTimer::begin(BenchStage stage) {
  if (queries_) queries_->stage[static_cast<int>(stage)].begin();
}

void StageDeviceTimer::end(BenchStage stage) {
  if (queries_) queries_->stage[static_cast<int>(stage)].end();
}

std::optional<double> StageDeviceTimer::seconds(BenchStage stage) const {
  if (!queries_) return std::nullopt;
  return 1e-9 * static_cast<double>(queries_->stage[static_cast<int>(stage)].elapsed_ns());
}

}  // namespace deformcd::app
