#include "bench_device_timer.h"

namespace deformcd::app {

// Without the GL backend there is no device to time.
struct StageDeviceTimer::Queries {};

StageDeviceTimer::StageDeviceTimer(bool /*gl*/) {}

StageDeviceTimer::~StageDeviceTimer() = default;

void StageDeviceTimer::begin(BenchStage /*stage*/) {}

void StageDeviceTimer::end(BenchStage /*stage*/) {}

std::optional<double> StageDeviceTimer::seconds(BenchStage /*stage*/) const {
  return std::nullopt;
}

}  // namespace deformcd::app
