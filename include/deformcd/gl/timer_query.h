#pragma once
/// \file timer_query.h
/// The device time of a stretch of GL commands, from a GL_TIME_ELAPSED query (core since GL
/// 3.3): how long the device took to run the commands issued between begin() and end(), where a
/// wall clock also counts the driver, the CPU's own work and the waits. On a GPU it is GPU time;
/// on a software rasterizer (llvmpipe, softpipe, swrast: see is_software_renderer in
/// deformcd/backend.h) the device is the CPU, and it is CPU time, however labelled.
///
/// Only one GL_TIME_ELAPSED query can be active in a context at a time (no nesting). Reading the
/// result waits for the commands measured: read it after the region timed by a wall clock (or
/// keep several queries in flight and read the oldest), so that it adds no wait to that region.

#include <cstdint>

namespace deformcd::gl {

/// One GL query object of target GL_TIME_ELAPSED. Move-only; a context must be current for every
/// call, including destruction.
class TimerQuery {
 public:
  /// Creates the query object.
  TimerQuery();
  ~TimerQuery();
  TimerQuery(TimerQuery&& other) noexcept;             ///< leaves `other` without a query
  TimerQuery& operator=(TimerQuery&& other) noexcept;  ///< leaves `other` without a query
  TimerQuery(const TimerQuery&) = delete;
  TimerQuery& operator=(const TimerQuery&) = delete;

  /// Starts timing the commands issued from now on. No other GL_TIME_ELAPSED query may be active.
  void begin();
  /// Stops timing; the result becomes available once the device has run the commands.
  void end();
  /// Whether the result of the last begin()/end() can be read without waiting.
  [[nodiscard]] bool ready() const;
  /// Nanoseconds the device spent on the commands of the last begin()/end(); waits for them
  /// when not ready().
  [[nodiscard]] std::uint64_t elapsed_ns() const;

 private:
  std::uint32_t name_ = 0;
};

}  // namespace deformcd::gl
