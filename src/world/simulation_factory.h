#pragma once
// Creates a world's simulation backend and contact response on the backend already chosen, the
// GL ones through backend_choice.h (which alone knows whether the GL backend was compiled in).

#include <memory>

#include "core/response/response_backend.h"
#include "core/sim/simulation_backend.h"
#include "cpu/executor.h"
#include "deformcd/backend.h"

namespace deformcd {

namespace gl {
class Context;
}

/// The GL simulation in `context` (kGl) or the CPU one on `executor` (kCpu).
[[nodiscard]] std::unique_ptr<sim::SimulationBackend> create_simulation(
    BackendKind kind, gl::Context* context, std::shared_ptr<cpu::Executor> executor);

/// The contact response that corrects `simulation` (made by create_simulation with the same
/// kind and context, after its upload) in place.
[[nodiscard]] std::unique_ptr<response::ResponseBackend> create_response(
    BackendKind kind, gl::Context* context, sim::SimulationBackend& simulation,
    std::shared_ptr<cpu::Executor> executor);

}  // namespace deformcd
