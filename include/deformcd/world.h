#pragma once
/// \file world.h
/// A world of deformable bodies stepped on a backend (OpenGL 4.3 compute, or the CPU).
///
///     deformcd::Scene scene = deformcd::read_scene("scenes/hanging.json");
///     deformcd::World world(deformcd::make_scene_bodies(scene, deformcd::read_tetgen, 300),
///                           deformcd::step_settings(scene.settings));
///     for (int i = 0; i < 300; ++i) world.step();
///     std::vector<glm::vec3> p = world.positions(0);

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "deformcd/error.h"
#include "deformcd/gpu_layout.h"
#include "deformcd/world_state.h"

namespace deformcd {

namespace gl {
class Context;
}
namespace sim {
class SimulationBackend;
}

/// Which backend steps a world.
enum class BackendKind {
  kAuto,  ///< GL when a 4.3 context can be had, else the CPU (with a notice)
  kGl,    ///< OpenGL 4.3 compute shaders; throws GlError when unavailable
  kCpu,   ///< multithreaded CPU (oneTBB)
};

/// "auto", "gl" or "cpu"; throws Error listing the valid names otherwise.
[[nodiscard]] BackendKind parse_backend(std::string_view name);

struct WorldOptions {
  BackendKind backend = BackendKind::kAuto;
  /// GL context to run in (e.g. gl::adopt_current_context() in an application that renders
  /// with OpenGL itself). When null, the world creates a headless one.
  gl::Context* gl_context = nullptr;
  /// CPU threads; 0 uses every core.
  int cpu_threads = 0;
  /// Frames between stability checks (each reads velocities back from a GL backend).
  int stability_check_interval = 10;
};

/// The simulation blew up: a state became NaN/Inf or a node moved implausibly far in a step.
class SimulationError : public Error {
 public:
  using Error::Error;
};

class World {
 public:
  /// Takes the bodies (see make_scene_bodies or build_body) and the step settings.
  /// Throws GlError (kGl without GL 4.3) or Error (buffers the device cannot hold).
  World(const std::vector<BodyInit>& bodies, const StepSettings& settings,
        const WorldOptions& options = {});
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Advances one frame (settings.substeps substeps of dt / substeps). Throws SimulationError
  /// naming the body and the frame when the state becomes unstable.
  void step();
  /// Frames stepped so far.
  [[nodiscard]] int frame() const { return frame_; }
  /// Waits until the backend has finished the work issued (for timing).
  void finish();

  [[nodiscard]] std::size_t body_count() const { return objects_.size(); }
  [[nodiscard]] const std::string& body_name(std::size_t body) const { return names_[body]; }
  /// Where body `body`'s nodes, springs and faces lie in the shared arrays and GL buffers.
  [[nodiscard]] const gpu::ObjectInfo& object(std::size_t body) const { return objects_[body]; }
  /// Current node positions of one body (read back from the backend).
  [[nodiscard]] std::vector<glm::vec3> positions(std::size_t body) const;
  /// Current node velocities of one body.
  [[nodiscard]] std::vector<glm::vec3> velocities(std::size_t body) const;

  /// "gl" or "cpu".
  [[nodiscard]] std::string_view backend_name() const;
  /// The device: GL renderer and version, or the CPU thread count.
  [[nodiscard]] std::string device() const;
  /// Things a user should know, one per line: why kAuto fell back to the CPU; a substep longer
  /// than the estimated stable one. Empty when there is nothing to say.
  [[nodiscard]] const std::string& notice() const { return notice_; }
  /// Estimated largest stable substep (s), a conservative bound (see stability_estimate.h).
  [[nodiscard]] double estimated_max_substep() const { return max_stable_substep_; }
  /// GL buffer name of all node positions (vec4, xyz + inverse mass; body i's nodes start at
  /// object(i).node_offset), for rendering without a CPU copy. 0 on the CPU backend.
  [[nodiscard]] std::uint32_t gl_position_buffer() const;

 private:
  void check_stability();
  [[nodiscard]] int suggested_substeps() const;

  std::unique_ptr<gl::Context> owned_context_;
  std::unique_ptr<sim::SimulationBackend> backend_;
  StepSettings settings_;
  int check_interval_;
  int frame_ = 0;
  std::vector<gpu::ObjectInfo> objects_;
  std::vector<std::string> names_;
  std::vector<float> body_sizes_;  // bounding-box diagonal at the start, for the blow-up test
  double max_stable_substep_ = 0.0;
  std::string notice_;
};

}  // namespace deformcd
