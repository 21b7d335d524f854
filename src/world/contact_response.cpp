#include "contact_response.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "deformcd/error.h"

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
}

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
                                 std::unique_ptr<response::ResponseBackend> backend)
    : settings_(settings),
      step_(step),
      simulation_(simulation),
      backend_(std::move(backend)),
      objects_(state.objects),
      node_body_(state.node_body) {
  check_response_settings(settings);
  float smallest_edge = INFINITY;
  for (const BodyInit& b : bodies) {
    const float edge = mean_surface_edge(b.body);
    mean_edge_.push_back(edge);
    smallest_edge = std::min(smallest_edge, edge);
    thickness_.push_back(settings.thickness.value_or(settings.relative_thickness * edge));
    carry_.push_back(b.carry_velocity);
  }
  max_untangle_step_ = settings.untangle_step * smallest_edge;
}

std::vector<glm::vec4> ContactResponse::body_motion() {
  // Each body drifts with the mean velocity of its nodes at the window's start; a node may stray
  // from its drifted path by twice what its own deviation from that mean would carry it in a
  // frame, plus what gravity adds, plus half the thickness so that resting bodies keep some
  // play. A node that strays farther starts a new search (project), so no pair is missed; the
  // drift keeps fast bodies from inflating every box by their speed.
  const SimulationState* state = simulation_.host_state();
  if (state == nullptr) simulation_.download_velocities(velocities_);
  const std::vector<glm::vec4>& v = state != nullptr ? state->velocities : velocities_;
  const float dt = step_.dt;
  std::vector<glm::vec4> motion(objects_.size());
  for (std::size_t b = 0; b < objects_.size(); ++b) {
    const gpu::ObjectInfo& o = objects_[b];
    glm::dvec3 sum(0.0);
    for (std::uint32_t i = o.node_offset; i < o.node_offset + o.node_count; ++i)
      sum += glm::dvec3(glm::vec3(v[i]));
    const glm::vec3 drift = glm::vec3(sum / static_cast<double>(o.node_count)) + carry_[b];
    float stray = 0.0f;
    for (std::uint32_t i = o.node_offset; i < o.node_offset + o.node_count; ++i)
      stray = std::max(stray, glm::length(glm::vec3(v[i]) + carry_[b] - drift));
    if (!std::isfinite(stray) || !std::isfinite(drift.x + drift.y + drift.z)) {
      throw SimulationError("the simulation became unstable: body " + std::to_string(b) +
                            " has a non-finite velocity. Use a smaller dt, more substeps or "
                            "softer springs");
    }
    // Capped at half a mean edge: a faster frame searches again when a node gets that far,
    // rather than inflating every box (the search's cost grows with the reach squared).
    const float travel = 2.0f * stray * dt + glm::length(step_.gravity) * dt * dt;
    const float cap = std::max(0.25f * mean_edge_[b], thickness_[b]);
    motion[b] = glm::vec4(drift, 0.5f * thickness_[b] + std::min(travel, cap));
  }
  return motion;
}

void ContactResponse::begin_frame(Detector& detector, std::vector<Contact> intersections) {
  detector_ = &detector;
  intersections_ = std::move(intersections);
  counts_ = {};
  search();
}

void ContactResponse::search() {
  Detector& detector = *detector_;
  const std::vector<Contact>& intersections = intersections_;
  elapsed_ = 0.0f;
  const std::uint64_t searches = counts_.searches + 1u;
  response::FrameConstraints c;
  c.body_motion = body_motion();
  std::vector<float> reach(objects_.size());
  std::vector<glm::vec3> drift(objects_.size());
  for (std::size_t b = 0; b < objects_.size(); ++b) {
    reach[b] = 0.5f * thickness_[b] + c.body_motion[b].w;
    drift[b] = glm::vec3(c.body_motion[b]) * step_.dt;
  }
  counts_ = {};
  counts_.searches = searches;
  for (const ProximityPair& p : detector.find_proximity(reach, drift)) {
    gpu::ContactPair pair{};
    const std::uint32_t first_a = objects_[p.mesh_a].node_offset;
    const std::uint32_t first_b = objects_[p.mesh_b].node_offset;
    const bool edges = p.kind == ProximityPair::Kind::kEdgeEdge;
    pair.nodes[0] = first_a + p.vertices[0];
    pair.nodes[1] = (edges ? first_a : first_b) + p.vertices[1];
    pair.nodes[2] = first_b + p.vertices[2];
    pair.nodes[3] = first_b + p.vertices[3];
    pair.kind = edges ? gpu::kContactEdgeEdge : gpu::kContactVertexFace;
    pair.thickness = 0.5f * (thickness_[p.mesh_a] + thickness_[p.mesh_b]);
    c.pairs.push_back(pair);
    ++(edges ? counts_.edge_edge : counts_.vertex_face);
  }
  // Untangling: each vertex of an intersecting face against the other face, unless it is one
  // of that face's own corners (self-intersections of faces sharing a node).
  for (const Contact& contact : intersections) {
    const ContactFace* sides[2] = {&contact.a, &contact.b};
    for (int s = 0; s < 2; ++s) {
      const ContactFace& mine = *sides[s];
      const ContactFace& other = *sides[1 - s];
      const std::uint32_t first_mine = objects_[mine.body].node_offset;
      const std::uint32_t first_other = objects_[other.body].node_offset;
      for (std::uint32_t k = 0; k < 3u; ++k) {
        const std::uint32_t v = first_mine + mine.nodes[k];
        gpu::ContactPair pair{};
        pair.nodes[0] = v;
        for (std::uint32_t j = 0; j < 3u; ++j)
          pair.nodes[j + 1u] = first_other + other.nodes[j];
        if (v == pair.nodes[1] || v == pair.nodes[2] || v == pair.nodes[3]) continue;
        pair.kind = gpu::kContactUntangle;
        pair.thickness = 0.5f * (thickness_[mine.body] + thickness_[other.body]);
        c.pairs.push_back(pair);
        ++counts_.untangle;
      }
    }
  }
  response::index_constraints_by_node(static_cast<std::uint32_t>(node_body_.size()), c);
  backend_->begin_frame(c);
}

void ContactResponse::project(float h, bool more_substeps) {
  elapsed_ += h;
  response::ContactConstants k{};
  k.h = h;
  k.elapsed = elapsed_;
  k.friction_static = settings_.friction_static;
  k.friction_dynamic = settings_.friction_dynamic;
  k.restitution = settings_.restitution;
  k.max_untangle_step = max_untangle_step_;
  if (backend_->project(k) && more_substeps) search();
}

}  // namespace deformcd
