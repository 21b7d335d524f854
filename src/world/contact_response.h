#pragma once
// The world's contact response stage (issue 12): at the start of each search window (the
// frame's, and more within it while the surfaces move fast) it gathers the constraints
// (proximity pairs from the detector, untangling pairs from the last exact intersections) and
// hands them to a response backend; after every substep it has the backend project them, and
// widens the window's search around the nodes that strayed beyond their reach.

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/response/response_backend.h"
#include "core/sim/simulation_backend.h"
#include "deformcd/collision.h"
#include "deformcd/detector.h"
#include "deformcd/response.h"
#include "deformcd/simulation_state.h"
#include "deformcd/world.h"

namespace deformcd {

namespace cpu {
class Executor;
}  // namespace cpu

class BodySleep;
class OverlapFinder;
class SelfContact;
class TangledPrimitives;

class ContactResponse {
 public:
  /// The surfaces' relative motion over a search window: about this many of the smallest
  /// body's mean surface edges at most.
  static constexpr float kWindowEdges = 1.0f;

  /// `bodies` as the world got them, `state` as assembled from them (node offsets, node
  /// bodies); `simulation` is read for velocities; `backend` corrects its state; `executor`
  /// runs the host's per-pair work (the world's CPU threads, on either backend). With
  /// `self_contact` each body's surface is kept apart from itself too (the detector must search
  /// each body against itself; SelfContact keeps the pairs of bodies moving as a whole).
  ContactResponse(const ResponseSettings& settings, const std::vector<BodyInit>& bodies,
                  const SimulationState& state, const StepSettings& step,
                  sim::SimulationBackend& simulation,
                  std::unique_ptr<response::ResponseBackend> backend,
                  std::shared_ptr<cpu::Executor> executor, bool self_contact);
  ~ContactResponse();
  ContactResponse(const ContactResponse&) = delete;
  ContactResponse& operator=(const ContactResponse&) = delete;

  /// Starts a frame: the constraints on the current positions are every proximity pair
  /// `detector` finds within each body's thickness and reach, and for each intersecting face
  /// pair of `intersections` (the last exact pass) its vertices against the other face.
  /// `detector` must outlive the frame.
  void begin_frame(Detector& detector, std::vector<Contact> intersections);
  /// The substeps of the frame begin_frame() began: the scene's, or more where
  /// ResponseSettings::substep_motion asks (motion_bounded_substeps).
  [[nodiscard]] int frame_substeps() const { return frame_substeps_; }
  /// One projection after a substep of length h. When `more_substeps` follow in the frame: if
  /// the window has ended, a new search begins the next one on the positions now; else, if a
  /// node has strayed beyond its reach, the window's search is widened around the strays
  /// (widen()), so no pair is missed. After the frame's last substep, the next begin_frame()
  /// searches anyway.
  void project(float h, bool more_substeps);
  /// Ends a frame (after its last projection): with ResponseSettings::sleep, the islands of
  /// bodies that have rested long enough fall asleep and those a moving body touched wake
  /// (BodySleep); their nodes' inverse masses change in the simulation.
  void end_frame();
  /// The gravity the next substeps apply (World::set_gravity): the nodes' reaches allow for it,
  /// and a change of load wakes every sleeping body (their rest was under the old one).
  void set_gravity(const glm::vec3& gravity);
  /// Whether body b is asleep (false without ResponseSettings::sleep).
  [[nodiscard]] bool asleep(std::size_t body) const;

  /// m: body b's contact thickness.
  [[nodiscard]] float thickness(std::size_t body) const { return thickness_[body]; }
  [[nodiscard]] const ResponseCounts& counts() const { return counts_; }

 private:
  /// Throws a SimulationError naming node `node` (global), its body and `what` it has; the world
  /// reports it with its own check (World::run_response).
  [[noreturn]] void unstable(std::uint32_t node, const char* what) const;
  /// The nodes' velocities now (the CPU state's, or read back from GL).
  [[nodiscard]] std::span<const glm::vec4> velocities();
  /// The nodes' positions now (the CPU state's, or read back from GL).
  [[nodiscard]] std::span<const glm::vec4> positions();
  /// The diagonal of the box of the surface nodes' velocities v (with their bodies' carry
  /// velocities): a bound on any two surface nodes' relative speed.
  [[nodiscard]] float relative_surface_speed(std::span<const glm::vec4> v) const;
  /// The frame's substeps for the frame's first window's constraints: the scene's, or as many
  /// as keep each pair's closing in a substep (its closing_speed x h) within substep_motion x
  /// the smallest thickness, at most kMaxSubstepFactor x the scene's.
  [[nodiscard]] int motion_bounded_substeps(const std::vector<gpu::ContactPair>& pairs) const;
  /// How many substeps a search window starting now lasts, the nodes at velocities v.
  [[nodiscard]] int window_substeps(std::span<const glm::vec4> v) const;
  /// Each node's path velocity and reach over a search window of `window` seconds, the nodes
  /// at velocities v.
  [[nodiscard]] std::vector<glm::vec4> node_motion(std::span<const glm::vec4> v, float window);
  /// A new search window from the positions now.
  void search();
  /// Within the window: the nodes that strayed get twice their deviation as reach, and their
  /// pairs are found again by widening the window's search (Detector::widen_proximity).
  void widen();
  /// Whether an edge-edge pair (global nodes, positions at the window's start) is a contact of
  /// its own: its closest points inside both edges, or, at an edge's end, that end vertex not
  /// over a face beside the other edge (over_a_face_beside; see add_proximity_pair).
  [[nodiscard]] bool edge_contact_of_its_own(const gpu::ContactPair& pair, std::uint32_t body_a,
                                             std::uint32_t body_b) const;
  /// Whether point p (positions at the window's start) is over a face beside edge (e0, e1)
  /// of `body` (global nodes), inside it by a margin: where its vertex-face pair holds it.
  [[nodiscard]] bool over_a_face_beside(std::uint32_t body, std::uint32_t e0, std::uint32_t e1,
                                        const glm::dvec3& p) const;
  /// Whether every body keeping its pairs with itself still may over the next substep, of
  /// length h (SelfContact::holds), on the positions and velocities now.
  [[nodiscard]] bool self_pairs_hold(float h);
  /// Lists a volume constraint for each tetrahedron of `body` (the next body: they come in
  /// order; its first node node_offset, its `thickness`: the thin ones are those less high at
  /// rest), unless volume_floor is 0 (an empty block).
  void add_volume_constraints(const Body& body, std::uint32_t node_offset, float thickness);
  /// Appends the volume constraints of the bodies that can move to c (after every other; the
  /// entries before them are listed_contacts_).
  void append_volume_constraints(response::FrameConstraints& c);
  /// What a proximity pair becomes (proximity_constraint).
  struct ProximityConstraint {
    gpu::ContactPair pair{};
    float distance = 0.0f;  // the pair's, where the window starts
    bool links = false;     // it joins its bodies (for the sleeping islands)
    bool acts = false;      // `pair` is a constraint of the window
  };
  /// Proximity pair p as a constraint (unless its primitives are tangled, it is an edge pair
  /// whose end a vertex-face pair holds, or its vertex starts behind its face), its distance
  /// measured where the window starts when `remeasure`; `node_motion` is the window's. Reads
  /// only what the window's start set: pairs can be made in parallel.
  [[nodiscard]] ProximityConstraint proximity_constraint(
      ProximityPair p, bool remeasure, const std::vector<glm::vec4>& node_motion) const;
  /// Appends proximity pairs `pairs` as constraints of c, in their order: made in parallel
  /// (proximity_constraint), then appended, linked and counted in order, so the list is the
  /// same on every thread count.
  void add_proximity_pairs(std::span<const ProximityPair> pairs, bool remeasure,
                           response::FrameConstraints& c);
  /// An untangling constraint (kContactUntangle: pushed out through the face's plane, its
  /// weights clamped into the face): vertex `vertex` of `body` against `face` (local nodes) of
  /// `other`.
  [[nodiscard]] gpu::ContactPair untangling_constraint(
      std::uint32_t body, std::uint32_t vertex, std::uint32_t other,
      const std::array<std::uint32_t, 3>& face) const;
  /// The frame's penetration constraints: for each two bodies the intersections join, every
  /// surface vertex of one inside the other against the face it leaves through along the
  /// pair's separating direction (OverlapFinder), on the positions now.
  void find_penetrations();
  /// Whether untangling constraint `pair` (a vertex of body `mine`, a face of body `other`)
  /// pushes the vertex along the way the two bodies come apart (their face's normal, at the
  /// window's start, within 90 degrees of it); true when the two do not overlap.
  [[nodiscard]] bool along_the_way_apart(std::uint32_t mine, std::uint32_t other,
                                         const gpu::ContactPair& pair) const;
  /// Notes that a constraint of the frame joins bodies a and b (for the sleeping islands).
  void link(std::uint32_t a, std::uint32_t b);
  /// Gives the bodies BodySleep put to sleep or woke (`changed`) their inverse masses in the
  /// simulation (zeros asleep, as given awake), and counts the sleeping bodies.
  void apply_sleep_changes(const std::vector<std::uint32_t>& changed);
  /// The thickness contacts between bodies a and b keep: the thinner body's (a == b: the
  /// body's, before self_thickness).
  [[nodiscard]] float pair_thickness(std::uint32_t a, std::uint32_t b) const;
  /// A self-contact pair's thickness: the body's, or half the pair's distance in the pose the
  /// body was given in (its rest shape), whichever is less.
  [[nodiscard]] float self_thickness(const gpu::ContactPair& pair) const;

  ResponseSettings settings_;
  StepSettings step_;
  sim::SimulationBackend& simulation_;
  std::unique_ptr<response::ResponseBackend> backend_;
  std::shared_ptr<cpu::Executor> executor_;
  std::vector<gpu::ObjectInfo> objects_;
  std::vector<std::uint32_t> node_body_;
  std::vector<std::string> names_;  // per body
  std::vector<glm::vec3> carry_;
  std::vector<glm::vec3> rest_;           // per node: where the body was given (at rest)
  std::vector<std::uint8_t> on_surface_;  // per node: a vertex of its body's collision surface
  /// A surface edge (local nodes a < b) and the third corners of the faces beside it.
  struct EdgeFaces {
    std::uint32_t a = 0, b = 0;
    std::uint32_t third[2] = {0, 0};
    std::uint32_t faces = 0;  // 1 or 2 (more: a non-manifold edge keeps the first two)
  };
  std::vector<std::vector<EdgeFaces>> edge_faces_;  // per body, sorted by (a, b)
  // Per body, per vertex v + 1: where the edges with a == v start in edge_faces_ (a CSR index:
  // over_a_face_beside scans a vertex's few edges instead of searching them all).
  std::vector<std::vector<std::uint32_t>> edge_first_;
  std::vector<float> thickness_;            // per body
  std::vector<float> mean_edge_;            // per body, surface
  std::vector<glm::vec4> velocities_;       // read back from a GL simulation
  std::vector<glm::vec4> positions_;        // read back from a GL simulation
  std::vector<glm::vec4> last_velocities_;  // per node, at the last search
  float max_untangle_step_ = 0.0f;
  /// The tetrahedra's volume constraints (kContactVolume), body after body: every window
  /// lists those of the bodies that can move, a body's as one block.
  std::vector<gpu::ContactPair> volume_floors_;
  std::vector<std::uint32_t> volume_begin_;  // per body + 1: where its volume constraints begin
  std::size_t listed_contacts_ = 0;     // constraints_.pairs' entries before its volume constraints
  Detector* detector_ = nullptr;        // of the frame
  std::vector<Contact> intersections_;  // of the frame
  std::unique_ptr<TangledPrimitives> tangled_;  // of the frame's intersections
  std::unique_ptr<OverlapFinder> overlap_;      // made from the detector's meshes when needed
  std::vector<gpu::ContactPair> penetrations_;  // of the frame (find_penetrations)
  /// Two bodies that overlap in the frame and the way a moves out of b (Overlap::direction).
  struct WayApart {
    std::uint32_t a = 0, b = 0;
    glm::vec3 direction{0.0f};
  };
  std::vector<WayApart> ways_apart_;              // of the frame (find_penetrations)
  response::FrameConstraints constraints_;        // of the window; the backend reads them
  response::FrameConstraints spare_constraints_;  // the window's before: the next one's storage
  std::vector<glm::vec3> window_start_;           // per node: where the window began
  float elapsed_ = 0.0f;                          // since the window began (the last search)
  float frame_time_ = 0.0f;                       // since the frame began
  int substep_ = 0;                               // substeps projected in the frame
  int window_end_ = 0;                            // the substep the window ends after
  int frame_substeps_ = 1;      // of the frame begin_frame() began (before: the scene's)
  float thinnest_ = 0.0f;       // m: the smallest body's thickness
  float smallest_edge_ = 0.0f;  // the smallest body's mean surface edge
  std::unique_ptr<SelfContact> self_contact_;  // with self-contact
  std::vector<std::uint8_t> self_kept_;        // per body: its pairs with itself are kept ones
  ResponseCounts counts_;
  std::unique_ptr<BodySleep> sleep_;  // with ResponseSettings::sleep
  std::vector<std::uint8_t> linked_;  // bodies x bodies: joined by a constraint in the frame
  /// bodies x bodies: the frame's exact pass found them intersecting (a body with itself too).
  std::vector<std::uint8_t> intersecting_;
  /// Whether body b cannot move now (a fixed base, a sleeping body: the simulation's
  /// FrozenBodies::can_move): a constraint between two such bodies has only nodes of inverse
  /// mass 0, so it never corrects anything.
  [[nodiscard]] bool immovable(std::uint32_t body) const;
};

/// Mean length of a body's surface edges (each edge once).
[[nodiscard]] float mean_surface_edge(const Body& body);

}  // namespace deformcd
