#include "bench_intersections.h"

#include <algorithm>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "deformcd/world_intersections.h"

namespace deformcd::app {

BenchIntersections::BenchIntersections(const World& world, const std::vector<BodyInit>& bodies)
    : bodies_(bodies) {
  // One thread: the census is not timed, and must not take a core from another engineer's run.
  if (world.responds()) census_ = std::make_unique<WorldIntersections>(world, 1);
}

BenchIntersections::~BenchIntersections() = default;

void BenchIntersections::record(std::vector<IntersectionCensus>& per_frame,
                                std::vector<std::uint64_t>& inverted) {
  if (census_ == nullptr) return;
  per_frame.push_back(census_->count());
  inverted.push_back(inverted_tetrahedra(census_->positions(), bodies_));
}

std::uint64_t inverted_tetrahedra(const std::vector<std::vector<glm::vec3>>& positions,
                                  const std::vector<BodyInit>& bodies) {
  std::uint64_t inverted = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const std::vector<glm::vec3>& x = positions[b];
    for (const Tetrahedron& t : bodies[b].body.tetrahedra) {
      const glm::dvec3 a(x[t[0]]);
      const double six_volume = glm::dot(
          glm::cross(glm::dvec3(x[t[1]]) - a, glm::dvec3(x[t[2]]) - a), glm::dvec3(x[t[3]]) - a);
      if (!(six_volume > 0.0)) ++inverted;
    }
  }
  return inverted;
}

void add_intersection_fields(nlohmann::json& per_frame,
                             const std::vector<IntersectionCensus>& census,
                             const std::vector<std::uint64_t>& inverted) {
  if (census.empty()) return;
  nlohmann::json between = nlohmann::json::array(), self = nlohmann::json::array(),
                 inside = nlohmann::json::array();
  for (const IntersectionCensus& c : census) {
    between.push_back(c.between_pairs);
    self.push_back(c.self_pairs);
    inside.push_back(c.inside_vertices);
  }
  per_frame["intersecting_pairs_between"] = between;
  per_frame["intersecting_pairs_self"] = self;
  per_frame["inside_vertices"] = inside;
  per_frame["inverted_tetrahedra"] = inverted;
}

void print_intersection_summary(std::ostream& out, const std::vector<IntersectionCensus>& census,
                                const std::vector<std::uint64_t>& inverted) {
  if (census.empty()) return;
  const auto frames = static_cast<std::size_t>(std::count_if(
      census.begin(), census.end(), [](const IntersectionCensus& c) { return c.any(); }));
  std::uint64_t between = 0, self = 0, inside = 0;
  for (const IntersectionCensus& c : census) {
    between = std::max(between, c.between_pairs);
    self = std::max(self, c.self_pairs);
    inside = std::max(inside, c.inside_vertices);
  }
  out << "                intersections (bodies with themselves included): " << frames << " of "
      << census.size() << " frames; the most in one frame: " << between << " pairs between bodies, "
      << self << " within a body, " << inside << " vertices inside another body; "
      << (inverted.empty() ? 0u : *std::max_element(inverted.begin(), inverted.end()))
      << " tetrahedra inverted\n";
}

}  // namespace deformcd::app
