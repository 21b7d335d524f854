#pragma once
/// \file world.h
/// A world of deformable bodies stepped on a backend (OpenGL 4.3 compute, or the CPU).
///
///     deformcd::Scene scene = deformcd::read_scene("scenes/hanging.json");
///     deformcd::World world(deformcd::make_scene_bodies(scene, deformcd::read_tetgen, 300),
///                           deformcd::step_settings(scene.settings));
///     for (int i = 0; i < 300; ++i) world.step();
///     std::vector<glm::vec3> p = world.positions(0);
///     std::vector<deformcd::Contact> c = world.contacts();  // the last frame's

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "deformcd/backend.h"
#include "deformcd/collision.h"
#include "deformcd/detector.h"
#include "deformcd/error.h"
#include "deformcd/gpu_layout.h"
#include "deformcd/response.h"
#include "deformcd/simulation_state.h"

namespace deformcd {

namespace gl {
class Context;
}
namespace sim {
class SimulationBackend;
}
namespace cpu {
class Executor;
}

/// How a World runs: backend, broad phase, self-collision, contact response, threads.
struct WorldOptions {
  BackendKind backend = BackendKind::kAuto;  ///< kAuto: GL on a hardware device, else the CPU
  /// GL context to run in (e.g. gl::adopt_current_context() in an application that renders
  /// with OpenGL itself). When null, the world creates a headless one.
  gl::Context* gl_context = nullptr;
  /// CPU threads (of the simulation and the collision detection); 0 uses every core. Results
  /// do not depend on it.
  int cpu_threads = 0;
  /// Frames between stability checks (each reads velocities back from a GL backend).
  int stability_check_interval = 10;
  /// Collision detection run after each frame's simulation; kNone skips it. Every broad phase
  /// finds the same contacts; kBvh is the fastest by far.
  BroadPhase broadphase = BroadPhase::kBvh;
  /// Each body also collides with itself (faces sharing an edge are never a contact; faces
  /// sharing a node are when they meet elsewhere too), in the detection and in the contact
  /// response. Unset: on exactly when `response` is set, since a response without it lets a
  /// soft body fold through itself where another presses it (the shipped impact: 185 of 200
  /// frames with self-intersecting triangles, 0 with it; docs/simulation-and-response.md,
  /// "Self-contact"). Fixed for the world's life.
  std::optional<bool> self_collision = std::nullopt;
  /// Time each stage of step() (see last_frame_times()): the world waits for the backend
  /// (glFinish on GL) after the simulation and after the collision pass, before reading the
  /// clock. Off by default, since waiting keeps the CPU from queueing the next frame's work.
  bool measure_stage_times = false;
  /// Contact response: bodies that touch push each other apart (and, with self_collision, a
  /// body its own folds). Unset: bodies pass through each other, as in the paper. Its
  /// untangling of intersecting surfaces needs a broad phase other than kNone.
  std::optional<ResponseSettings> response = std::nullopt;
};

/// Wall time of the stages of one step(), in seconds (0 when not measured).
struct FrameTimes {
  double simulation_s = 0.0;  ///< substeps (forces, integration), and the stability check
  double collision_s = 0.0;   ///< bounds, broad phase, narrow phase
  double proximity_s = 0.0;   ///< the contact response's pair search (once a frame)
  double response_s = 0.0;    ///< the contact response's projections (after every substep)
};

/// The contact constraints at the end of the last frame: its last search's, with the pairs of
/// the widenings since (all 0 without response).
struct ResponseCounts {
  std::uint64_t vertex_face = 0;  ///< vertex-triangle proximity pairs
  std::uint64_t edge_edge = 0;    ///< edge-edge proximity pairs
  std::uint64_t untangle = 0;     ///< vertices of intersecting faces pushed out
  /// Surface vertices of one body inside another (found when the frame began with the two
  /// intersecting), each pushed out through the face it leaves by along the pair's separating
  /// direction (deformcd/overlap.h).
  std::uint64_t penetrating = 0;
  /// Proximity searches in the frame: one, plus one each time a node strayed beyond the reach
  /// the last one assumed.
  std::uint64_t searches = 0;
  /// Times in the frame a search was widened instead: around the nodes that strayed, only
  /// their pairs found again with larger reaches (Detector::widen_proximity).
  std::uint64_t widenings = 0;
  /// Bodies searched against themselves in the frame (with self-contact): a body's
  /// self-contact pairs are kept from one such search until its surface has deformed (or turned)
  /// by a margin, not searched again every window.
  std::uint64_t self_searches = 0;
  /// Substeps the frame took: the scene's, or more where ResponseSettings::substep_motion asked.
  std::uint64_t substeps = 0;
  /// Sweeps the frame's projections ran, all substeps together: `iterations` each,
  /// and more where an active contact was still deeper than half its thickness (up to 4 x).
  std::uint64_t iterations = 0;
  /// Bodies asleep after the frame (ResponseSettings::sleep).
  std::uint64_t asleep = 0;
  /// m: the closest two primitives of a proximity constraint were when the frame's searches
  /// found them (on the positions the response left), relative to that pair's thickness in
  /// closest_thickness (the gap the response keeps): the smallest distance / thickness of the
  /// frame's proximity constraints. Infinity and 0 when the frame had none.
  float closest_distance = std::numeric_limits<float>::infinity();
  /// m: the thickness of the pair that gave closest_distance (0 when the frame had none).
  float closest_thickness = 0.0f;

  /// Of contact_constraints(), those between two different bodies (the rest are each body's
  /// own, with self-contact: a body's near pairs with itself are constraints in every frame, in
  /// contact with another body or not).
  std::uint64_t between_bodies = 0;

  /// The contact constraints (not the volume constraints): proximity pairs, untangling and
  /// penetrating vertices.
  [[nodiscard]] std::uint64_t contact_constraints() const {
    return vertex_face + edge_edge + untangle + penetrating;
  }
};

/// Where a simulation blew up, as SimulationError::site() gives it (the message says the same
/// in words); a field that is not known is -1 or empty.
struct BlowUpSite {
  /// The check that found it: "simulation" (the world's check of the state after the substeps)
  /// or "response" (the contact response's check of the state the integration gave it).
  std::string stage = "simulation";
  /// The frame being stepped when it was found, from 1.
  int frame = -1;
  /// The body's index in the scene, and its name.
  std::int64_t body = -1;
  /// The body's name (BodyInit::name).
  std::string body_name;
  /// The node's index within the body.
  std::int64_t node = -1;
};

/// The simulation blew up: a state became NaN/Inf or a node moved implausibly far in a step.
class SimulationError : public Error {
 public:
  /// `message` states what happened and what to change; `site` the same as fields.
  explicit SimulationError(const std::string& message, BlowUpSite site = {})
      : Error(message), site_(std::move(site)) {}
  /// Where it blew up (for programs that record it, such as a study's rows).
  [[nodiscard]] const BlowUpSite& site() const noexcept { return site_; }

 private:
  BlowUpSite site_;
};

class ContactResponse;

/// A mass-spring simulation of tetrahedral bodies on the GL or the CPU backend, composed with
/// a Detector over their surfaces (docs/simulation-and-response.md).
class World {
 public:
  /// Takes the bodies (see make_scene_bodies or build_body) and the step settings.
  /// Throws GlError (kGl without GL 4.3) or Error (buffers the device cannot hold).
  World(const std::vector<BodyInit>& bodies, const StepSettings& settings,
        const WorldOptions& options = {});
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Advances one frame (settings.substeps substeps of dt / substeps), then detects the
  /// collisions between different bodies (and within each body, with self_collision) with the
  /// broad phase set (see broadphase()). Throws SimulationError naming the body and the frame
  /// when the state becomes unstable.
  void step();
  /// Frames stepped so far.
  [[nodiscard]] int frame() const { return frame_; }
  /// The stage times of the last step() when WorldOptions::measure_stage_times is set.
  [[nodiscard]] const FrameTimes& last_frame_times() const { return last_times_; }
  /// Waits until the backend has finished the work issued (for timing).
  void finish();

  [[nodiscard]] std::size_t body_count() const {
    return objects_.size();
  }  ///< bodies, in the order given
  [[nodiscard]] const std::string& body_name(std::size_t body) const {
    return names_[body];
  }  ///< body `body`'s name
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
  /// Largest stable substep (s) of the system linearized at rest, the springs' damping included:
  /// a conservative bound (block Gershgorin, see src/core/sim/stability_estimate.h).
  [[nodiscard]] double estimated_max_substep() const { return max_stable_substep_; }
  /// The broad phase step() runs; every one finds the same contacts.
  [[nodiscard]] BroadPhase broadphase() const { return broadphase_; }
  /// Switches the broad phase from the next step() on (e.g. a viewer's key).
  void set_broadphase(BroadPhase method) { broadphase_ = method; }
  /// m/s^2: the gravity the next step() applies (StepSettings::gravity at the start).
  [[nodiscard]] glm::vec3 gravity() const { return settings_.gravity; }
  /// Changes the gravity from the next step() on: a platform or a camera tilting, a ramp of
  /// load instead of a step. Throws Error, changing nothing, when a component is not finite.
  void set_gravity(const glm::vec3& gravity);
  /// The collision detector over the bodies' surfaces (mesh i = body i, its triangles the
  /// body's surface faces, its positions the simulation's, read in place).
  [[nodiscard]] const Detector& detector() const { return *detector_; }
  /// Runs collision detection now on the current positions with broadphase() (as step() does
  /// after the simulation), e.g. after set_broadphase() or for the initial pose.
  void detect_collisions();
  /// Counts of the last collision pass (all 0 before the first or with kNone). On GL this waits
  /// for the pass.
  [[nodiscard]] CollisionCounts collision_counts() const;
  /// The intersecting face pairs of the last collision pass, sorted by (a.body, a.face, b.body,
  /// b.face), a.body <= b.body; the same on every backend and broad phase.
  [[nodiscard]] std::vector<Contact> contacts() const;
  /// Per surface face of every body (body i's faces start at object(i).face_offset): 1 when the
  /// face was in a contact in the last pass, else 0.
  [[nodiscard]] std::vector<std::uint32_t> face_flags() const;
  /// GL buffer name of those flags (the paper's SSBO 5, one uint per face), for rendering
  /// without a CPU copy. 0 on the CPU backend.
  [[nodiscard]] std::uint32_t gl_face_flag_buffer() const;
  /// The 64 leaf boxes per body as the last octree pass computed them (body i's at 64 i).
  [[nodiscard]] std::vector<gpu::Box> leaf_boxes() const;
  /// Whether contact response is on (WorldOptions::response).
  [[nodiscard]] bool responds() const { return response_ != nullptr; }
  /// m: body `body`'s contact thickness (0 without response).
  [[nodiscard]] float contact_thickness(std::size_t body) const;
  /// The contact constraints of the last step (all 0 without response).
  [[nodiscard]] ResponseCounts response_counts() const;
  /// Whether body `body` is asleep after the last step (ResponseSettings::sleep): its nodes
  /// hold still until a moving body touches its island.
  [[nodiscard]] bool asleep(std::size_t body) const;
  /// Surface faces of all bodies (global node indices), as in the GL face buffer.
  [[nodiscard]] const std::vector<gpu::Face>& faces() const { return faces_; }

  /// GL buffer name of all node positions (vec4, xyz + inverse mass; body i's nodes start at
  /// object(i).node_offset), for rendering without a CPU copy. 0 on the CPU backend.
  [[nodiscard]] std::uint32_t gl_position_buffer() const;

 private:
  /// Throws a SimulationError naming the first node (by body) whose position or velocity is
  /// not finite or would cross half its body in a substep, `frame` the frame it is found in and
  /// `where` (may be empty) where it was met, with the suggested substeps.
  void check_stability(int frame, const char* where, const char* stage);
  // The substeps of the frame being stepped (or the last one): the scene's, or more where the
  // response's motion-bounded substeps asked.
  [[nodiscard]] int frame_substeps() const;
  /// Runs a step of the contact response; a blow-up it meets (a SimulationError) is reported
  /// with the world's check, which knows the frame and the suggested substeps.
  void run_response(const std::function<void()>& stage);
  [[nodiscard]] int suggested_substeps() const;
  /// What to change after a blow-up: the step's settings and the suggested substeps.
  [[nodiscard]] std::string advice() const;

  // Destroyed last to first: the detector and the simulation before the context they run in.
  std::unique_ptr<gl::Context> owned_context_;
  std::shared_ptr<cpu::Executor> executor_;
  std::unique_ptr<sim::SimulationBackend> backend_;
  std::unique_ptr<Detector> detector_;
  std::unique_ptr<ContactResponse> response_;
  StepSettings settings_;
  int check_interval_;
  int frame_ = 0;
  std::vector<gpu::ObjectInfo> objects_;
  std::vector<std::string> names_;
  std::vector<float> body_sizes_;  // bounding-box diagonal at the start, for the blow-up test
  double max_stable_substep_ = 0.0;
  std::string notice_;
  BroadPhase broadphase_ = BroadPhase::kBvh;
  bool measure_stage_times_ = false;
  FrameTimes last_times_;
  bool detected_ = false;  // the last step ran a collision pass: its results are there
  std::vector<gpu::Face> faces_;
};

}  // namespace deformcd
