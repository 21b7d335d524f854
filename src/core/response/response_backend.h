#pragma once
// The contact response's line to a backend (issue 12): the world hands it each frame's
// constraints, then asks for one projection after every substep. The CPU backend
// (src/cpu/cpu_contact_response.h) and the GL backend implement it over the simulation's own
// positions and velocities, in place.

#include "core/response/contact_constraints.h"
#include "core/response/frame_constraints.h"

namespace deformcd::response {

class ResponseBackend {
 public:
  virtual ~ResponseBackend() = default;
  ResponseBackend(const ResponseBackend&) = delete;
  ResponseBackend& operator=(const ResponseBackend&) = delete;

  /// Takes a search window's constraints and records the current positions as its start (w =
  /// the node's reach, node_motion[n].w). A backend may read `constraints` in every project()
  /// without a copy of its own (the CPU's does): the caller keeps them alive and unchanged
  /// until it hands the backend constraints again.
  virtual void begin_frame(const FrameConstraints& constraints) = 0;
  /// Replaces the constraints of the window begin_frame() started (a widened search's: the
  /// pairs of the nodes that strayed found again with larger reaches): the window's start
  /// positions stay, and each node's reach becomes node_motion[n].w of the new constraints.
  /// `constraints` may be the same object as before, changed since (kept as begin_frame's).
  virtual void update_frame(const FrameConstraints& constraints) = 0;
  /// The projection after a substep, on the current positions and velocities: the deviation,
  /// activity and count passes once, then `iterations` (>= 1) Gauss-Seidel sweeps over the
  /// active constraints in the colours of response::SweepOrder (see contact_constraints.h), and
  /// more, to
  /// kMaxIterationFactor x `iterations` in all, while an active contact is still violated
  /// (contact_violated; the friction's last-iteration rule in each of those). Returns whether a
  /// free node ends it beyond its reach (apply_correction): the window's constraints no longer
  /// cover every pair, and a new search must begin one.
  [[nodiscard]] virtual bool project(const ContactConstants& constants, int iterations) = 0;
  /// The iterations the last project() ran.
  [[nodiscard]] virtual int last_iterations() const = 0;

 protected:
  ResponseBackend() = default;
};

}  // namespace deformcd::response
