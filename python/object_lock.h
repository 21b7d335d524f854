#pragma once
// How a bound object is shared between Python threads. Each Detector / World wrapper has a
// mutex that every call holds while it uses the C++ object, so that one thread's detect() (run
// without the GIL, letting other Python threads go on) never overlaps another thread's
// set_positions() (which would drop an array the pass is reading). The mutex is only ever
// waited for with the GIL released: a thread holding the GIL never waits for it, so a thread
// that holds the mutex can always get the GIL back (NumPy releases it during large copies).

#include <mutex>

#include <pybind11/pybind11.h>

namespace deformcd::python {

// Locks `mutex`, waiting for it without the GIL; returns with the GIL held again.
[[nodiscard]] inline std::unique_lock<std::mutex> lock_object(std::mutex& mutex) {
  pybind11::gil_scoped_release no_gil;
  return std::unique_lock<std::mutex>(mutex);
}

// Runs `work` (pure C++, touching no Python object) with the object locked and the GIL released.
template <typename Work>
decltype(auto) without_gil(std::mutex& mutex, Work&& work) {
  pybind11::gil_scoped_release no_gil;
  const std::lock_guard<std::mutex> lock(mutex);
  return work();
}

}  // namespace deformcd::python
