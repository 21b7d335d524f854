
#include "world/contact_response.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <utility>

#include "core/collision/primitive_distance.h"
#include "core/geometry.h"
#include "core/response/contact_constraints.h"
#include "cpu/executor.h"
#include "cpu/parallel_for.h"
#include "deformcd/error.h"
#include "deformcd/overlap.h"
#include "world/body_sleep.h"
#include "world/self_contact.h"

namespace deformcd {

namespace {

void check_value(const char* name, float value, float high = INFINITY) {
  if (!std::isfinite(value) || value < 0.0f || value > high) {
    throw Error(std::string("response ") + name + " must be " +
                (std::isfinite(high) ? "between 0 and " + std::to_string(high)
                                     : std::string("finite and >= 0")) +
                ", not " + std::to_string(value));
  }
}

}  // namespace

// The primitive pairs of the faces the last exact pass found intersecting: each vertex of one
// face against the other face, each edge of one against each edge of the other (global nodes).
// Their proximity constraints are left out: across an intersection their directions point the
// wrong way (two crossed edges are pushed apart on the sides they crossed to, a vertex through
// a face is held at the face's back within the thickness) and they would hold the surfaces
// tangled against the untangling constraints, which take those faces apart.
class TangledPrimitives {
 public:
  TangledPrimitives(const std::vector<Contact>& intersections,
                    const std::vector<gpu::ObjectInfo>& objects) {
    for (const Contact& c : intersections) {
      std::array<std::uint32_t, 3> a{}, b{};
      for (std::uint32_t k = 0; k < 3u; ++k) {
        a[k] = objects[c.a.body].node_offset + c.a.nodes[k];
        b[k] = objects[c.b.body].node_offset + c.b.nodes[k];
      }
      add_face_pair(a, b);
      add_face_pair(b, a);
    }
    std::sort(keys_.begin(), keys_.end());
  }

  [[nodiscard]] bool holds(const gpu::ContactPair& pair) const {
    if (keys_.empty()) return false;
    const std::array<std::uint32_t, 4> key =
        pair.kind == gpu::kContactEdgeEdge
            ? edge_pair_key(pair.nodes[0], pair.nodes[1], pair.nodes[2], pair.nodes[3])
            : vertex_face_key(pair.nodes[0], {pair.nodes[1], pair.nodes[2], pair.nodes[3]});
    return std::binary_search(keys_.begin(), keys_.end(), key);
  }

 private:
  static std::array<std::uint32_t, 4> vertex_face_key(std::uint32_t v,
                                                      std::array<std::uint32_t, 3> face) {
    std::sort(face.begin(), face.end());
    return {v, face[0], face[1], face[2]};
  }
  // Unordered in both edges and in their order (an edge pair has one key).
  static std::array<std::uint32_t, 4> edge_pair_key(std::uint32_t a0, std::uint32_t a1,
                                                    std::uint32_t b0, std::uint32_t b1) {
    std::array<std::uint32_t, 4> key{std::min(a0, a1), std::max(a0, a1), std::min(b0, b1),
                                     std::max(b0, b1)};
    if (std::pair{key[2], key[3]} < std::pair{key[0], key[1]}) {
      std::swap(key[0], key[2]);
      std::swap(key[1], key[3]);
    }
    return key;
  }
  void add_face_pair(const std::array<std::uint32_t, 3>& a, const std::array<std::uint32_t, 3>& b) {
    for (std::uint32_t i = 0; i < 3u; ++i) {
      keys_.push_back(vertex_face_key(a[i], b));
      for (std::uint32_t j = 0; j < 3u; ++j)
        keys_.push_back(edge_pair_key(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]));
    }
  }

  std::vector<std::array<std::uint32_t, 4>> keys_;
};

void check_response_settings(const ResponseSettings& s) {
  if (s.thickness.has_value()) {
    check_value("thickness", *s.thickness);
    if (!(*s.thickness > 0.0f)) throw Error("response thickness must be positive, not 0");
  }
  check_value("relative_thickness", s.relative_thickness);
  if (!(s.relative_thickness > 0.0f)) {
    throw Error("response relative_thickness must be positive, not 0");
  }
  check_value("friction_static", s.friction_static);
  check_value("friction_dynamic", s.friction_dynamic);
  if (s.friction_dynamic > s.friction_static) {
    throw Error("response friction_dynamic (" + std::to_string(s.friction_dynamic) +
                ") must not exceed friction_static (" + std::to_string(s.friction_static) + ")");
  }
  check_value("restitution", s.restitution, 1.0f);
  check_value("untangle_step", s.untangle_step);
  if (!(s.untangle_step > 0.0f)) throw Error("response untangle_step must be positive, not 0");
  check_value("substep_motion", s.substep_motion);
  check_value("volume_floor", s.volume_floor);
  if (!(s.volume_floor < 1.0f)) {
    throw Error("response volume_floor must be below 1, not " + std::to_string(s.volume_floor));
  }
  if (s.iterations < 1 || s.iterations > kMaxResponseIterations) {
    throw Error("response iterations must be between 1 and " +
                std::to_string(kMaxResponseIterations) + ", not " + std::to_string(s.iterations));
  }
  if (s.sleep.has_value()) {
    check_value("sleep speed", s.sleep->speed);
    check_value("sleep time", s.sleep->time);
    if (!(s.sleep->speed > 0.0f)) throw Error("response sleep speed must be positive, not 0");
    if (!(s.sleep->time > 0.0f)) throw Error("response sleep time must be positive, not 0");
  }
}

namespace {

// Tetrahedron t's least height at rest: 3 x its rest volume over its largest face's area (the
// areas of the body's starting pose, which a scene's `squash` deforms a little).
float least_rest_height(const Body& body, std::size_t t) {
  const Tetrahedron& n = body.tetrahedra[t];
  const glm::vec3 x[4] = {glm::vec3(body.positions[n[0]]), glm::vec3(body.positions[n[1]]),
                          glm::vec3(body.positions[n[2]]), glm::vec3(body.positions[n[3]])};
  float largest = 0.0f;
  for (int skip = 0; skip < 4; ++skip) {
    const glm::vec3& a = x[(skip + 1) % 4];
    const glm::vec3& b = x[(skip + 2) % 4];
    const glm::vec3& c = x[(skip + 3) % 4];
    largest = std::max(largest, 0.5f * glm::length(glm::cross(b - a, c - a)));
  }
  return largest > 0.0f ? 3.0f * body.tet_rest_volume[t] / largest : 0.0f;
}

}  // namespace

float mean_surface_edge(const Body& body) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  double sum = 0.0;
  for (const gpu::Face& f : body.faces) {
    const std::uint32_t v[3] = {f.a, f.b, f.c};
    for (int k = 0; k < 3; ++k) {
      if (!edges.insert(std::minmax(v[k], v[(k + 1) % 3])).second) continue;
      sum += glm::length(body.positions[v[k]] - body.positions[v[(k + 1) % 3]]);
    }
  }
  return edges.empty() ? 0.0f : static_cast<float>(sum / static_cast<double>(edges.size()));
}

ContactResponse::ContactResponse(const ResponseSettings& settings,
                                 const std::vector<BodyInit>& bodies, const SimulationState& state,
                                 const StepSettings& step, sim::SimulationBackend& simulation,
                                 std::unique_ptr<response::ResponseBackend> backend,
                                 std::shared_ptr<cpu::Executor> executor, bool self_contact)
    : settings_(settings),
      step_(step),
      simulation_(simulation),
      backend_(std::move(backend)),
      executor_(std::move(executor)),
      objects_(state.objects),
      node_body_(state.node_body) {
  check_response_settings(settings);
  float smallest_edge = INFINITY;
  for (std::uint32_t body = 0; body < bodies.size(); ++body) {
    const BodyInit& b = bodies[body];
    names_.push_back(b.name);
    const float edge = mean_surface_edge(b.body);
    mean_edge_.push_back(edge);
    smallest_edge = std::min(smallest_edge, edge);
    thickness_.push_back(settings.thickness.value_or(settings.relative_thickness * edge));
    add_volume_constraints(b.body, state.objects[body].node_offset, thickness_.back());
    carry_.push_back(b.carry_velocity);
    for (const glm::vec4& x : b.body.positions)
      rest_.emplace_back(x);
  }
  on_surface_.assign(node_body_.size(), 0u);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    std::vector<EdgeFaces> edges;
    for (const gpu::Face& f : bodies[b].body.faces) {
      const std::uint32_t v[3] = {f.a, f.b, f.c};
      for (int k = 0; k < 3; ++k) {
        on_surface_[objects_[b].node_offset + v[k]] = 1u;
        const std::uint32_t lo = std::min(v[k], v[(k + 1) % 3]);
        const std::uint32_t hi = std::max(v[k], v[(k + 1) % 3]);
        EdgeFaces e;
        e.a = lo;
        e.b = hi;
        e.third[0] = v[(k + 2) % 3];
        e.faces = 1;
        edges.push_back(e);
      }
    }
    // One entry per edge with both faces' third corners, in face order.
    std::stable_sort(edges.begin(), edges.end(), [](const EdgeFaces& x, const EdgeFaces& y) {
      return std::pair(x.a, x.b) < std::pair(y.a, y.b);
    });
    std::vector<EdgeFaces>& merged = edge_faces_.emplace_back();
    for (const EdgeFaces& e : edges) {
      if (!merged.empty() && merged.back().a == e.a && merged.back().b == e.b) {
        if (merged.back().faces < 2u) merged.back().third[merged.back().faces++] = e.third[0];
      } else {
        merged.push_back(e);
      }
    }
    std::vector<std::uint32_t>& first = edge_first_.emplace_back(objects_[b].node_count + 1u, 0u);
    for (const EdgeFaces& e : merged)
      ++first[e.a + 1u];
    for (std::size_t v = 1; v < first.size(); ++v)
      first[v] += first[v - 1u];
  }
  if (self_contact)
    self_contact_ = std::make_unique<SelfContact>(objects_, on_surface_, thickness_);
  max_untangle_step_ = settings.untangle_step * smallest_edge;
  smallest_edge_ = smallest_edge;
  thinnest_ = *std::min_element(thickness_.begin(), thickness_.end());
  frame_substeps_ = step.substeps;  // until the first frame's search sets it
  linked_.assign(bodies.size() * bodies.size(), 0u);
  intersecting_.assign(bodies.size() * bodies.size(), 0u);
  if (settings.sleep.has_value()) {
    std::vector<float> inverse_mass(state.positions.size());
    for (std::size_t i = 0; i < inverse_mass.size(); ++i)
      inverse_mass[i] = state.positions[i].w;
    std::vector<std::uint8_t> may_sleep;  // a body carried along a path never rests
    may_sleep.reserve(bodies.size());
    for (const BodyInit& b : bodies)
      may_sleep.push_back(b.carry_velocity == glm::vec3(0.0f) ? 1u : 0u);
    sleep_ = std::make_unique<BodySleep>(*settings.sleep, objects_, std::move(inverse_mass),
                                         mean_edge_, may_sleep, step.dt);
  }
}

void ContactResponse::unstable(std::uint32_t node, const char* what) const {
  const std::uint32_t b = node_body_[node];
  // The world adds the frame and what to change (World::run_response).
  throw SimulationError("body " + std::to_string(b) + " ('" + names_[b] + "') node " +
                            std::to_string(node - objects_[b].node_offset) + " has " + what +
                            " (found by the contact response's check), " +
                            std::to_string(frame_time_) + " s into the frame",
                        {.stage = "response",
                         .body = static_cast<std::int64_t>(b),
                         .body_name = names_[b],
                         .node = static_cast<std::int64_t>(node - objects_[b].node_offset)});
}

std::span<const glm::vec4> ContactResponse::velocities() {
  const sim::NodeBuffers nodes = simulation_.node_buffers();
  if (nodes.host_velocities != nullptr) return {nodes.host_velocities, nodes.node_count};
  simulation_.download_velocities(velocities_);
  return velocities_;
}

std::span<const glm::vec4> ContactResponse::positions() {
  const sim::NodeBuffers nodes = simulation_.node_buffers();
  if (nodes.host_positions != nullptr) return {nodes.host_positions, nodes.node_count};
  simulation_.download_positions(positions_);
  return positions_;
}

float ContactResponse::relative_surface_speed(std::span<const glm::vec4> v) const {
  // The diagonal of the box of the surface nodes' velocities: at least the speed of any surface
  // node relative to any other.
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (std::size_t b = 0; b < objects_.size(); ++b) {
    const gpu::ObjectInfo& o = objects_[b];
    for (std::uint32_t i = o.node_offset; i < o.node_offset + o.node_count; ++i) {
      if (on_surface_[i] == 0u) continue;
      const glm::vec3 velocity = glm::vec3(v[i]) + carry_[b];
      lo = glm::min(lo, velocity);
      hi = glm::max(hi, velocity);
    }
  }
  return glm::length(hi - lo);
}

int ContactResponse::motion_bounded_substeps(const std::vector<gpu::ContactPair>& pairs) const {
  // The fastest closing of the window's pairs along their straight paths: the relative speed
  // of all surface nodes (the window's bound) would count the bodies' ringing, which closes
  // nothing, and on the impact asked for 60-100 substeps instead of 16 once the bodies met.
  float closing = 0.0f;
  for (const gpu::ContactPair& p : pairs)
    closing = std::max(closing, p.closing_speed);
  if (!(closing > 0.0f) || !std::isfinite(closing)) return step_.substeps;
  // In double: a blown-up speed must not overflow the int it becomes (it is capped).
  const double needed = std::ceil(static_cast<double>(closing) * step_.dt /
                                  (static_cast<double>(settings_.substep_motion) * thinnest_));
  const double most = static_cast<double>(kMaxSubstepFactor) * step_.substeps;
  return static_cast<int>(std::clamp(needed, static_cast<double>(step_.substeps), most));
}

int ContactResponse::window_substeps(std::span<const glm::vec4> v) const {
  // The window is as long as the surfaces' relative motion covers at most about a mean edge:
  // every pair that can close over the window is a candidate, and the candidates (their search
  // and each substep's activity pass) cost more than searches do, so a fast approach is
  // searched in short windows. On the impact scene (one thread, 80 frames) that took 12-15 %
  // off proximity + response against windows to the frame's end, and the stack's 8 %; windows
  // of half or twice that motion cost 5-10 % more than this one.
  const int remaining = frame_substeps_ - substep_;
  const float relative = relative_surface_speed(v);
  if (!(relative > 0.0f) || !std::isfinite(relative)) return remaining;
  const float h = step_.dt / static_cast<float>(frame_substeps_);
  const float span = kWindowEdges * smallest_edge_ / (relative * h);
  if (!(span < static_cast<float>(remaining))) return remaining;
  return std::max(1, static_cast<int>(std::ceil(span)));
}

std::vector<glm::vec4> ContactResponse::node_motion(std::span<const glm::vec4> v, float window) {
  // Each node is predicted to go on at its velocity over the window (plus its body's carry
  // velocity) and may stray from that straight path by its reach: a quarter of the thickness
  // of play (the search adds the constraint's half of the thickness to it), what gravity adds
  // over the window, and what its velocity would add if it went on changing at the rate it
  // changed since the last search (up to half a mean edge). That rate is taken over at least the
  // window: a search a substep or two after the last one would otherwise take a contact's
  // impulse for a steady acceleration (on the impact scene that doubled the frame-start search's
  // cost). The play trades candidates against searches: on the impact scene a quarter of the
  // thickness costs about 15 % less than the whole thickness, and a tenth more again. A node
  // that strays farther starts a new search (project), so no pair is missed. Prediction per node
  // keeps both sides of a contact, which move together, from sweeping across each other, and a
  // fast body's boxes from growing by more than its own motion; a reach per node keeps the few
  // ringing or braking nodes from starting a search every few substeps without growing every
  // node's. Nodes on no collision surface never enter a pair: their reach is infinite, so they
  // never start a search.
  if (last_velocities_.size() != v.size()) last_velocities_.assign(v.begin(), v.end());
  // A node's velocity changed by |dv| since the last search, elapsed_ ago (the last window's
  // time, not yet reset): at that rate (|dv| x change_rate), over the window its deviation from
  // the straight path grows to 1/2 rate window^2.
  const float change_rate = 1.0f / std::max(elapsed_, window);
  std::vector<glm::vec4> motion(node_body_.size());
  for (std::size_t b = 0; b < objects_.size(); ++b) {
    const gpu::ObjectInfo& o = objects_[b];
    const float base = 0.25f * thickness_[b] + 0.5f * glm::length(step_.gravity) * window * window;
    const float most = 0.5f * mean_edge_[b];
    for (std::uint32_t i = o.node_offset; i < o.node_offset + o.node_count; ++i) {
      const glm::vec3 velocity = glm::vec3(v[i]) + carry_[b];
      if (!std::isfinite(velocity.x + velocity.y + velocity.z))
        unstable(i, "a non-finite velocity");
      const float change = 0.5f * glm::length(glm::vec3(v[i]) - glm::vec3(last_velocities_[i])) *
                           change_rate * window * window;
      const float reach = base + std::min(change, most);
      motion[i] = glm::vec4(velocity, on_surface_[i] != 0u ? reach : INFINITY);
    }
  }
  last_velocities_.assign(v.begin(), v.end());
  return motion;
}

float ContactResponse::pair_thickness(std::uint32_t a, std::uint32_t b) const {
  // The finer surface decides: the thickness is a body's skin for its own mesh's scale (a share
  // of its mean edge), and a coarse body's would hold a fine one far off it (a 3 mm slab rested
  // 8.2 mm above a plate whose edges are 11 times its own with the two thicknesses' mean: 15.1
  // and 1.35 mm). The search reaches stay each body's half of its own thickness, which covers
  // every pair within the thinner one.
  return std::min(thickness_[a], thickness_[b]);
}

float ContactResponse::self_thickness(const gpu::ContactPair& pair) const {
  // Primitives of one body that are closer than the thickness where the body rests (on real
  // meshes, a few hundred pairs one edge apart: 192-1,674 on the shipped models at 0.2 x the
  // mean edge, none on the plate) would push each other apart for ever; they keep half their rest
  // distance instead, which still keeps them from passing through each other.
  const glm::vec3 x[4] = {rest_[pair.nodes[0]], rest_[pair.nodes[1]], rest_[pair.nodes[2]],
                          rest_[pair.nodes[3]]};
  // Most pairs are farther apart at rest than twice the thickness: the distance between the two
  // primitives' boxes (a lower bound on theirs, in double from the float corners) says so for
  // them without the closest points. The margin of 1e-6 of it covers the rounding of the exact
  // distance to float, so that the answer is the exact one's.
  const std::uint32_t split = pair.kind == gpu::kContactEdgeEdge ? 2u : 1u;
  glm::dvec3 lo_a(x[0]), hi_a(x[0]), lo_b(x[split]), hi_b(x[split]);
  for (std::uint32_t k = 1; k < 4u; ++k) {
    const glm::dvec3 p(x[k]);
    if (k < split) {
      lo_a = glm::min(lo_a, p);
      hi_a = glm::max(hi_a, p);
    } else if (k > split) {
      lo_b = glm::min(lo_b, p);
      hi_b = glm::max(hi_b, p);
    }
  }
  const glm::dvec3 gap = glm::max(glm::max(lo_b - hi_a, lo_a - hi_b), glm::dvec3(0.0));
  const double apart = 2.0 * static_cast<double>(pair.thickness) * (1.0 + 1e-6);
  if (glm::dot(gap, gap) >= apart * apart) return pair.thickness;
  // Half, for most: a body resting under load presses such pairs, and a larger share keeps them
  // pushing and the body awake (0.9 for every pair: none of a pile's twelve bodies asleep by
  // frame 480). Edges that pass each other at rest (closest points inside both, as across a
  // concave notch) keep 0.9: there a vertex's fan slides under the other edge, and with half
  // the contacts crushed the pair until the edges went through each other (the lion of the
  // impact, 4 of 26 perturbed starts; none with 0.9).
  constexpr float kRestShare = 0.5f;
  constexpr float kPassingEdgesRestShare = 0.9f;
  float share = kRestShare;
  if (pair.kind == gpu::kContactEdgeEdge) {
    double s = 0.0;
    double t = 0.0;
    if (collision::segment_closest_parameters(glm::dvec3(x[0]), glm::dvec3(x[1]), glm::dvec3(x[2]),
                                              glm::dvec3(x[3]), s, t) &&
        s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0)
      share = kPassingEdgesRestShare;
  }
  return std::min(pair.thickness, share * collision::primitive_distance(pair.kind, x));
}

void ContactResponse::begin_frame(Detector& detector, std::vector<Contact> intersections) {
  detector_ = &detector;
  frame_time_ = 0.0f;
  substep_ = 0;
  intersections_ = std::move(intersections);
  tangled_ = std::make_unique<TangledPrimitives>(intersections_, objects_);
  counts_ = {};
  std::fill(linked_.begin(), linked_.end(), std::uint8_t{0});
  std::fill(intersecting_.begin(), intersecting_.end(), std::uint8_t{0});
  const std::size_t n = objects_.size();
  for (const Contact& c : intersections_) {
    intersecting_[c.a.body * n + c.b.body] = 1u;
    intersecting_[c.b.body * n + c.a.body] = 1u;
  }
  find_penetrations();
  search();
}

void ContactResponse::find_penetrations() {
  penetrations_.clear();
  ways_apart_.clear();
  // The pairs of different bodies the frame's intersections join (begin_frame's intersecting_),
  // in (a, b) order.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> joined;
  const auto n = static_cast<std::uint32_t>(objects_.size());
  for (std::uint32_t a = 0; a < n; ++a)
    for (std::uint32_t b = a + 1u; b < n; ++b)
      if (intersecting_[a * n + b] != 0u) joined.emplace_back(a, b);
  if (joined.empty()) return;
  const Detector& detector = *detector_;
  if (!overlap_) {
    std::vector<CollisionMesh> meshes;
    for (std::size_t m = 0; m < detector.mesh_count(); ++m)
      meshes.push_back(detector.mesh(m));
    overlap_ = std::make_unique<OverlapFinder>(std::move(meshes));
  }
  const std::span<const glm::vec4> x = positions();
  const auto body_positions = [&](std::uint32_t b) {
    const gpu::ObjectInfo& o = objects_[b];
    std::vector<glm::vec3> p(o.node_count);
    for (std::uint32_t i = 0; i < o.node_count; ++i)
      p[i] = glm::vec3(x[o.node_offset + i]);
    return p;
  };
  // A vertex of `inner` against the triangle of `outer` it leaves through.
  const auto add = [&](std::uint32_t inner, std::uint32_t outer, const PenetratingVertex& v) {
    penetrations_.push_back(
        untangling_constraint(inner, v.vertex, outer, detector.mesh(outer).triangles[v.triangle]));
  };
  for (const auto& [a, b] : joined) {
    link(a, b);
    if (immovable(a) && immovable(b)) continue;
    const Overlap o = overlap_->find(a, b, body_positions(a), body_positions(b));
    if (o.any()) ways_apart_.push_back({a, b, o.direction});
    for (const PenetratingVertex& v : o.a_in_b)
      add(a, b, v);
    for (const PenetratingVertex& v : o.b_in_a)
      add(b, a, v);
  }
}

gpu::ContactPair ContactResponse::untangling_constraint(
    std::uint32_t body, std::uint32_t vertex, std::uint32_t other,
    const std::array<std::uint32_t, 3>& face) const {
  gpu::ContactPair pair{};
  pair.nodes[0] = objects_[body].node_offset + vertex;
  for (std::uint32_t k = 0; k < 3u; ++k)
    pair.nodes[k + 1u] = objects_[other].node_offset + face[k];
  pair.kind = gpu::kContactUntangle;
  pair.thickness = pair_thickness(body, other);
  pair.gap = -INFINITY;  // always awake
  pair.closing_speed = 0.0f;
  return pair;
}

bool ContactResponse::along_the_way_apart(std::uint32_t mine, std::uint32_t other,
                                          const gpu::ContactPair& pair) const {
  for (const WayApart& w : ways_apart_) {
    if (!(w.a == mine && w.b == other) && !(w.a == other && w.b == mine)) continue;
    const glm::vec3 away = w.a == mine ? w.direction : -w.direction;
    const glm::vec3 p1 = window_start_[pair.nodes[1]];
    const glm::vec3 normal =
        glm::cross(window_start_[pair.nodes[2]] - p1, window_start_[pair.nodes[3]] - p1);
    return glm::dot(normal, away) > 0.0f;
  }
  return true;
}

void ContactResponse::link(std::uint32_t a, std::uint32_t b) {
  linked_[std::min(a, b) * objects_.size() + std::max(a, b)] = 1u;
}

void ContactResponse::end_frame() {
  if (!sleep_) return;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> links;
  const auto n = static_cast<std::uint32_t>(objects_.size());
  for (std::uint32_t a = 0; a < n; ++a)
    for (std::uint32_t b = a; b < n; ++b)
      if (linked_[a * n + b] != 0u) links.emplace_back(a, b);
  // The bodies with a tetrahedron inside out (of those the volume floor holds: every one,
  // unless the floor is off) stay awake while their floors restore them.
  const std::span<const glm::vec4> x = positions();
  std::vector<std::uint8_t> inverted(objects_.size(), 0u);
  for (std::uint32_t b = 0; b + 1u < volume_begin_.size(); ++b) {
    if (sleep_->asleep(b)) continue;
    for (std::uint32_t t = volume_begin_[b]; t < volume_begin_[b + 1u]; ++t) {
      const auto corner = [&](std::uint32_t k) {
        return glm::dvec3(glm::vec3(x[volume_floors_[t].nodes[k]]));
      };
      if (!(geom::signed_volume6(corner(0), corner(1), corner(2), corner(3)) > 0.0)) {
        inverted[b] = 1u;
        break;
      }
    }
  }
  apply_sleep_changes(sleep_->end_frame(x, links, inverted));
}

void ContactResponse::set_gravity(const glm::vec3& gravity) {
  if (gravity == step_.gravity) return;
  step_.gravity = gravity;
  if (sleep_) apply_sleep_changes(sleep_->wake_all());
}

void ContactResponse::apply_sleep_changes(const std::vector<std::uint32_t>& changed) {
  for (const std::uint32_t b : changed) {
    const std::vector<float> inverse_mass = sleep_->inverse_masses(b);
    simulation_.set_inverse_masses(objects_[b].node_offset, inverse_mass);
  }
  counts_.asleep = sleep_->asleep_count();
}

bool ContactResponse::asleep(std::size_t body) const {
  return sleep_ && sleep_->asleep(body);
}

bool ContactResponse::immovable(std::uint32_t body) const {
  return !simulation_.frozen_bodies().can_move(body);
}

void ContactResponse::search() {
  Detector& detector = *detector_;
  const std::vector<Contact>& intersections = intersections_;
  const std::uint64_t searches = counts_.searches + 1u;
  // Built in the storage of the window before last (on the impact, 55,000 constraints: a new
  // list each search cost its allocation and page faults).
  response::FrameConstraints c = std::move(spare_constraints_);
  c.pairs.clear();
  // The window ends with the frame at the latest, since the next begin_frame() searches anyway:
  // a search that a stray node starts mid-frame sweeps the nodes over the frame's rest, not a
  // whole frame (on the impact scene the frame's last search kept about 6,500 candidates
  // instead of 29,000, and the results did not change); and earlier when the surfaces move
  // fast (window_substeps).
  const std::span<const glm::vec4> node_velocity = velocities();
  if (substep_ == 0) frame_substeps_ = step_.substeps;  // until the pairs below ask for more
  const int substeps = window_substeps(node_velocity);
  window_end_ = substep_ + substeps;
  const float window = window_end_ == frame_substeps_ ? step_.dt - frame_time_
                                                      : static_cast<float>(substeps) * step_.dt /
                                                            static_cast<float>(frame_substeps_);
  c.node_motion = node_motion(node_velocity, window);
  elapsed_ = 0.0f;
  // The detector's vertices are the surface nodes, in node order, body after body; the search
  // window lasts at most a frame. A vertex's search reach is its body's half of the thickness
  // plus its node's reach (interior nodes, on no surface, are not the detector's vertices'
  // concern: any finite value does).
  std::vector<float> reach(node_body_.size());
  std::vector<glm::vec3> motion(node_body_.size());
  for (std::size_t i = 0; i < node_body_.size(); ++i) {
    motion[i] = glm::vec3(c.node_motion[i]) * window;
    reach[i] =
        0.5f * thickness_[node_body_[i]] + (on_surface_[i] != 0u ? c.node_motion[i].w : 0.0f);
  }
  const ResponseCounts frame_so_far = counts_;
  counts_ = {};
  counts_.searches = searches;
  counts_.widenings = frame_so_far.widenings;
  counts_.self_searches = frame_so_far.self_searches;
  counts_.substeps = static_cast<std::uint64_t>(frame_substeps_);
  counts_.iterations = frame_so_far.iterations;
  counts_.closest_distance = frame_so_far.closest_distance;  // the frame's, not the window's
  counts_.closest_thickness = frame_so_far.closest_thickness;
  // The positions now: the window's start, kept for the side each vertex-face pair's vertex
  // starts on (also for pairs a widening finds later in the window).
  const std::span<const glm::vec4> x = positions();
  window_start_.resize(x.size());
  for (std::uint32_t i = 0; i < x.size(); ++i) {
    window_start_[i] = glm::vec3(x[i]);
    if (!std::isfinite(x[i].x + x[i].y + x[i].z)) unstable(i, "a non-finite position");
  }
  c.window_start = window_start_;
  // Bodies that cannot move (a fixed base, a sleeping body) are still: the search leaves out
  // the pairs between two of them, whose constraints could correct nothing (every node has
  // inverse mass 0). Their sleeping islands stay whole without those links (BodySleep).
  std::vector<std::uint8_t> still(objects_.size());
  for (std::uint32_t b = 0; b < still.size(); ++b)
    still[b] = immovable(b) ? 1u : 0u;
  // Bodies that move as a whole keep their pairs with themselves from a search of their own
  // (SelfContact); the window's search finds the others' and the pairs between bodies, and
  // widen() widens it.
  std::vector<std::uint8_t> search_self;
  if (self_contact_) {
    std::vector<std::uint8_t> movable(objects_.size());
    for (std::uint32_t b = 0; b < movable.size(); ++b)
      movable[b] = 1u - still[b];
    SelfContact::Plan plan = self_contact_->plan(window_start_, c.node_motion, window, movable);
    if (std::find(plan.search.begin(), plan.search.end(), 1u) != plan.search.end()) {
      self_contact_->take(detector.find_proximity(self_contact_->search_reach(), {}, {},
                                                  {.between = false, .within = plan.search}),
                          window_start_, plan.search);
      for (std::uint32_t b = 0; b < plan.search.size(); ++b) {
        if (plan.search[b] == 0u) continue;
        plan.kept[b] = 1u;
        ++counts_.self_searches;
      }
    }
    self_kept_ = std::move(plan.kept);
    search_self.resize(objects_.size());
    for (std::uint32_t b = 0; b < objects_.size(); ++b)
      search_self[b] = 1u - self_kept_[b];
  }
  add_proximity_pairs(detector.find_proximity(reach, motion, still, {.within = search_self}), false,
                      c);
  for (std::uint32_t b = 0; b < self_kept_.size(); ++b)
    if (self_kept_[b] != 0u) add_proximity_pairs(self_contact_->pairs(b), true, c);
  // Untangling: each vertex of an intersecting face against the other face, unless it is one
  // of that face's own corners (self-intersections of faces sharing a node).
  for (const Contact& contact : intersections) {
    const ContactFace* sides[2] = {&contact.a, &contact.b};
    for (int s = 0; s < 2; ++s) {
      const ContactFace& mine = *sides[s];
      const ContactFace& other = *sides[1 - s];
      for (std::uint32_t k = 0; k < 3u; ++k) {
        const gpu::ContactPair pair =
            untangling_constraint(mine.body, mine.nodes[k], other.body, other.nodes);
        const std::uint32_t v = pair.nodes[0];
        if (v == pair.nodes[1] || v == pair.nodes[2] || v == pair.nodes[3]) continue;
        // Two bodies that overlap come apart one way (their penetration constraints'): a face
        // pushes a vertex only along it. Pushed through the planes of every face they cross,
        // the contour's vertices held the bodies tangled (half_overlap.json: 175 vertices still
        // inside after 1 s; with this rule none from frame 12 on).
        if (!along_the_way_apart(mine.body, other.body, pair)) continue;
        link(mine.body, other.body);
        if (immovable(mine.body) && immovable(other.body)) continue;
        c.pairs.push_back(pair);
        ++counts_.untangle;
        if (mine.body != other.body) ++counts_.between_bodies;
      }
    }
  }
  // Deep overlap: the vertices inside another body, out along the pair's way apart (the
  // untangling above takes the crossing faces apart, but no face of the other body is near a
  // vertex deep inside it).
  c.pairs.insert(c.pairs.end(), penetrations_.begin(), penetrations_.end());
  counts_.penetrating = penetrations_.size();
  counts_.between_bodies += penetrations_.size();  // a vertex of one body inside another
  append_volume_constraints(c);
  // The frame's first search sets its substeps from how fast its pairs can close
  // (substep_motion); the window keeps its length in seconds.
  if (substep_ == 0 && settings_.substep_motion > 0.0f) {
    const int n = motion_bounded_substeps(c.pairs);
    if (n != frame_substeps_) {
      window_end_ = window_end_ == frame_substeps_
                        ? n
                        : std::min(n, (window_end_ * n + frame_substeps_ - 1) / frame_substeps_);
      frame_substeps_ = n;
    }
  }
  std::swap(constraints_, c);
  spare_constraints_ = std::move(c);
  backend_->begin_frame(constraints_);
}

void ContactResponse::append_volume_constraints(response::FrameConstraints& c) {
  // Last in the list (the backends solve them after the contacts): every tetrahedron of a
  // body that can move, a body's as one block (on the impact, 50,000 of the list's 55,000
  // entries, listed again at every search and widening).
  listed_contacts_ = c.pairs.size();
  std::size_t volumes = 0;
  for (std::uint32_t b = 0; b + 1u < volume_begin_.size(); ++b)
    if (!immovable(b)) volumes += volume_begin_[b + 1u] - volume_begin_[b];
  // Room for the widenings' new contacts too: a list grown to the exact size would move
  // whole at the next widening that adds one.
  const std::size_t needed = c.pairs.size() + volumes;
  if (c.pairs.capacity() < needed) c.pairs.reserve(needed + needed / 4u);
  for (std::uint32_t b = 0; b + 1u < volume_begin_.size(); ++b) {
    if (immovable(b)) continue;
    c.pairs.insert(c.pairs.end(), volume_floors_.begin() + volume_begin_[b],
                   volume_floors_.begin() + volume_begin_[b + 1u]);
  }
}

void ContactResponse::add_volume_constraints(const Body& body, std::uint32_t node_offset,
                                             float thickness) {
  if (volume_begin_.empty()) volume_begin_.push_back(0u);
  if (settings_.volume_floor > 0.0f) {
    for (std::size_t t = 0; t < body.tetrahedra.size(); ++t) {
      gpu::ContactPair pair{};
      for (std::uint32_t k = 0; k < 4u; ++k)
        pair.nodes[k] = node_offset + body.tetrahedra[t][k];
      pair.kind = gpu::kContactVolume;
      pair.thickness = settings_.volume_floor * body.tet_rest_volume[t];
      // Thin: a push of the body's thickness may take a corner through the opposite face.
      pair.side = least_rest_height(body, t) < thickness ? 1.0f : 0.0f;
      pair.gap = -INFINITY;  // always awake: the activity pass looks at its volume
      pair.step_limit = body.tet_rest_edge[t];
      pair.converge = 1.0f;  // iterate while below half the floor (contact_violated)
      volume_floors_.push_back(pair);
    }
  }
  volume_begin_.push_back(static_cast<std::uint32_t>(volume_floors_.size()));
}

bool ContactResponse::self_pairs_hold(float h) {
  if (std::find(self_kept_.begin(), self_kept_.end(), 1u) == self_kept_.end()) return true;
  const std::span<const glm::vec4> x = positions();
  const std::span<const glm::vec4> v = velocities();
  for (std::uint32_t b = 0; b < self_kept_.size(); ++b)
    if (self_kept_[b] != 0u && !self_contact_->holds(b, x, v, h)) return false;
  return true;
}

ContactResponse::~ContactResponse() = default;

ContactResponse::ProximityConstraint ContactResponse::proximity_constraint(
    ProximityPair p, bool remeasure, const std::vector<glm::vec4>& node_motion) const {
  ProximityConstraint out;
  gpu::ContactPair& pair = out.pair;
  const std::uint32_t first_a = objects_[p.mesh_a].node_offset;
  const std::uint32_t first_b = objects_[p.mesh_b].node_offset;
  const bool edges = p.kind == ProximityPair::Kind::kEdgeEdge;
  pair.nodes[0] = first_a + p.vertices[0];
  pair.nodes[1] = (edges ? first_a : first_b) + p.vertices[1];
  pair.nodes[2] = first_b + p.vertices[2];
  pair.nodes[3] = first_b + p.vertices[3];
  pair.kind = edges ? gpu::kContactEdgeEdge : gpu::kContactVertexFace;
  const glm::vec3 corners[4] = {window_start_[pair.nodes[0]], window_start_[pair.nodes[1]],
                                window_start_[pair.nodes[2]], window_start_[pair.nodes[3]]};
  // A kept self pair's distance where this window starts (the constraint's gap is measured
  // from there), not on the positions of the search that found it.
  if (remeasure) p.distance = collision::primitive_distance(pair.kind, corners);
  // An edge pair whose closest point is an edge's end is that vertex against the other edge.
  // Where the vertex is over a face beside that edge, the vertex-face pair with that face holds
  // it along the face's normal, and this one would push along the slanted line from the edge:
  // a step where the surfaces slide over each other (a block creeping on a slab held with
  // friction 0.5 on 28 degrees, where Coulomb says it slides; docs/notes/2026-12-04-friction.md).
  // A vertex against a convex edge (over neither face beside it) keeps its pair.
  if (edges && !edge_contact_of_its_own(pair, p.mesh_a, p.mesh_b)) return out;
  // (Pairs of two bodies that cannot move are not searched for: search() flags them still.)
  out.links = true;
  if (tangled_->holds(pair)) return out;
  pair.thickness = pair_thickness(p.mesh_a, p.mesh_b);
  // A self pair the rest-distance rule makes thinner keeps holding its vertex to the body's
  // thickness behind the face (its edges to that depth through each other): a guard of half a
  // sliver's rest distance (0.31 mm on a dragon of the pile, whose thickness is 3.4 mm) is
  // crossed within one substep, and a vertex past it was let go as if it had tunnelled (the
  // pile with self-contact, the floor and motion-bounded substeps: 4 self-intersecting pairs at
  // frame 27; none there with this).
  pair.hold_depth = pair.thickness;
  if (p.mesh_a == p.mesh_b) pair.thickness = self_thickness(pair);
  // Bodies that start the frame intersecting are taken apart over substeps (contact_violated).
  pair.converge = intersecting_[p.mesh_a * objects_.size() + p.mesh_b] != 0u ? 0.0f : 1.0f;
  pair.gap = p.distance - pair.thickness;
  const glm::vec3 velocity[4] = {
      glm::vec3(node_motion[pair.nodes[0]]), glm::vec3(node_motion[pair.nodes[1]]),
      glm::vec3(node_motion[pair.nodes[2]]), glm::vec3(node_motion[pair.nodes[3]])};
  pair.closing_speed = collision::closing_speed(pair.kind, velocity);
  if (edges) {
    // The side the edges pass each other on, so that edges that go through each other within
    // the window are taken back (response::contact_geometry).
    pair.side = response::edge_edge_start_side(corners);
  } else {
    pair.side = response::vertex_face_side(corners);
    // A vertex that starts the window behind the face never acts on it (contact_geometry): the
    // constraint would only cost its activity pass every substep (about a tenth of the impact
    // scene's vertex-face candidates).
    if (!(pair.side > 0.0f)) return out;
  }
  out.distance = p.distance;
  out.acts = true;
  return out;
}

void ContactResponse::add_proximity_pairs(std::span<const ProximityPair> pairs, bool remeasure,
                                          response::FrameConstraints& c) {
  std::vector<ProximityConstraint> made(pairs.size());
  executor_->run([&] {
    cpu::parallel_for(
        pairs.size(),
        [&](std::size_t i) { made[i] = proximity_constraint(pairs[i], remeasure, c.node_motion); },
        256);
  });
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const ProximityConstraint& m = made[i];
    if (m.links) link(pairs[i].mesh_a, pairs[i].mesh_b);
    if (!m.acts) continue;
    c.pairs.push_back(m.pair);
    ++(m.pair.kind == gpu::kContactEdgeEdge ? counts_.edge_edge : counts_.vertex_face);
    if (pairs[i].mesh_a != pairs[i].mesh_b) ++counts_.between_bodies;
    // The closest relative to its thickness (a cross-multiplied comparison: thickness > 0).
    if (m.distance * counts_.closest_thickness < counts_.closest_distance * m.pair.thickness ||
        counts_.closest_thickness == 0.0f) {
      counts_.closest_distance = m.distance;
      counts_.closest_thickness = m.pair.thickness;
    }
  }
}

bool ContactResponse::edge_contact_of_its_own(const gpu::ContactPair& pair, std::uint32_t body_a,
                                              std::uint32_t body_b) const {
  const glm::dvec3 x[4] = {
      glm::dvec3(window_start_[pair.nodes[0]]), glm::dvec3(window_start_[pair.nodes[1]]),
      glm::dvec3(window_start_[pair.nodes[2]]), glm::dvec3(window_start_[pair.nodes[3]])};
  double s = 0.0, t = 0.0;
  if (!collision::segment_closest_parameters(x[0], x[1], x[2], x[3], s, t)) return true;
  const bool end_of_a = s == 0.0 || s == 1.0;
  const bool end_of_b = t == 0.0 || t == 1.0;
  if (!end_of_a && !end_of_b) return true;  // the edges pass each other: an edge contact
  if (end_of_a && over_a_face_beside(body_b, pair.nodes[2], pair.nodes[3], s == 0.0 ? x[0] : x[1]))
    return false;
  if (end_of_b && over_a_face_beside(body_a, pair.nodes[0], pair.nodes[1], t == 0.0 ? x[2] : x[3]))
    return false;
  return true;
}

bool ContactResponse::over_a_face_beside(std::uint32_t body, std::uint32_t e0, std::uint32_t e1,
                                         const glm::dvec3& p) const {
  const std::uint32_t first = objects_[body].node_offset;
  const std::uint32_t lo = std::min(e0, e1) - first, hi = std::max(e0, e1) - first;
  const std::vector<EdgeFaces>& edges = edge_faces_[body];
  const std::vector<std::uint32_t>& first_of = edge_first_[body];
  const auto it = std::find_if(edges.begin() + first_of[lo], edges.begin() + first_of[lo + 1u],
                               [&](const EdgeFaces& e) { return e.b == hi; });
  if (it == edges.begin() + first_of[lo + 1u]) return false;  // not a surface edge
  const glm::dvec3 a(window_start_[first + lo]), b(window_start_[first + hi]);
  for (std::uint32_t f = 0; f < it->faces; ++f) {
    // Inside the face by 1e-3 of it on every side (the vertex-face pairs' weights, in double):
    // there the vertex-face pair with this face holds p, even after rounding. A vertex right
    // above the edge or its end (stacked grids) is on no face by that margin and keeps this pair.
    const glm::dvec3 c(window_start_[first + it->third[f]]);
    glm::dvec3 uvw(0.0);
    constexpr double kMargin = 1e-3;
    if (response::plane_barycentric(p, a, b, c, uvw) && uvw.x > kMargin && uvw.y > kMargin &&
        uvw.z > kMargin)
      return true;
  }
  return false;
}

void ContactResponse::widen() {
  // The nodes beyond their reach, as the backend judged them (apply_correction, on the same
  // floats): the positions now against the window's start carried along each node's path.
  const std::span<const glm::vec4> x = positions();
  std::vector<glm::vec4>& node_motion = constraints_.node_motion;
  std::vector<std::uint32_t> strays;
  std::vector<float> reach;
  std::vector<std::uint8_t> strayed(x.size(), 0u);
  for (std::uint32_t i = 0; i < x.size(); ++i) {
    // Fixed nodes never stray, nor do nodes on no surface (their reach is infinite).
    if (!(x[i].w > 0.0f) || on_surface_[i] == 0u) continue;
    const float old_reach = node_motion[i].w;
    const float deviation = response::path_deviation(
        glm::vec3(x[i]), glm::vec4(window_start_[i], old_reach), node_motion[i], elapsed_);
    if (!(deviation > old_reach)) continue;
    if (!std::isfinite(2.0f * deviation)) unstable(i, "a non-finite position");
    // Room for its deviation to double before it strays again.
    node_motion[i].w = 2.0f * deviation;
    strays.push_back(i);
    reach.push_back(0.5f * thickness_[node_body_[i]] + node_motion[i].w);
    strayed[i] = 1u;
  }
  if (strays.empty()) {  // not expected: the backend said a node strayed
    search();
    return;
  }
  // Their old pairs go; the widened search's come instead. The others' pairs, a kept body's
  // pairs with itself (which still hold) and the untangling constraints stand; the volume
  // constraints go to the end again, after the new pairs.
  std::vector<gpu::ContactPair>& pairs = constraints_.pairs;
  pairs.resize(listed_contacts_);
  std::erase_if(pairs, [&](const gpu::ContactPair& p) {
    if (p.kind == gpu::kContactUntangle) return false;
    const std::uint32_t body = node_body_[p.nodes[0]];
    if (body == node_body_[p.nodes[3]] && !self_kept_.empty() && self_kept_[body] != 0u)
      return false;
    const bool gone = strayed[p.nodes[0]] != 0u || strayed[p.nodes[1]] != 0u ||
                      strayed[p.nodes[2]] != 0u || strayed[p.nodes[3]] != 0u;
    if (!gone) return false;
    --(p.kind == gpu::kContactEdgeEdge ? counts_.edge_edge : counts_.vertex_face);
    if (body != node_body_[p.nodes[3]]) --counts_.between_bodies;
    return true;
  });
  add_proximity_pairs(detector_->widen_proximity(strays, reach), false, constraints_);
  append_volume_constraints(constraints_);
  ++counts_.widenings;
  backend_->update_frame(constraints_);
}

void ContactResponse::project(float h, bool more_substeps) {
  elapsed_ += h;
  frame_time_ += h;
  response::ContactConstants k{};
  k.h = h;
  k.elapsed = elapsed_;
  k.friction_static = settings_.friction_static;
  k.friction_dynamic = settings_.friction_dynamic;
  k.restitution = settings_.restitution;
  // untangle_step bounds a substep's untangling, whatever the iterations: each takes its share.
  k.max_untangle_step = max_untangle_step_ / static_cast<float>(settings_.iterations);
  ++substep_;
  const bool strayed = backend_->project(k, settings_.iterations);
  counts_.iterations += static_cast<std::uint64_t>(backend_->last_iterations());
  if (!more_substeps) return;  // the next begin_frame() searches
  if (substep_ >= window_end_ || !self_pairs_hold(h)) {
    search();
  } else if (strayed) {
    widen();
  }
}

}  // namespace deformcd
