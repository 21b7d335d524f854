#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/geometry.h"
#include "core/spring_topology.h"
#include "core/surface_extraction.h"
#include "deformcd/body.h"
#include "deformcd/error.h"
#include "deformcd/limits.h"

namespace deformcd {

namespace {

// BodyOptions::node_mass_floor: every mass raised to at least `share` x the mean, then all
// scaled back to the total, summed in index order.
void floor_node_masses(std::vector<double>& mass, double share) {
  if (!(share > 0.0) || mass.empty()) return;
  double total = 0.0;
  for (const double m : mass)
    total += m;
  const double least = share * total / static_cast<double>(mass.size());
  double raised = 0.0;
  for (double& m : mass) {
    m = std::max(m, least);
    raised += m;
  }
  const double scale = total / raised;
  for (double& m : mass)
    m *= scale;
}

}  // namespace

Body build_body(const TetMesh& mesh, const BodyOptions& options, const std::string& source) {
  if (!(options.density > 0.0) || !std::isfinite(options.density)) {
    throw InputError(source, "density must be positive and finite");
  }
  if (!(options.stiffness > 0.0) || !std::isfinite(options.stiffness)) {
    throw InputError(source, "stiffness must be positive and finite");
  }
  if (!(options.node_mass_floor >= 0.0 && options.node_mass_floor <= 1.0)) {
    throw InputError(source, "node_mass_floor must be between 0 and 1");
  }
  Body body;
  body.tetrahedra = mesh.tetrahedra;

  body.positions.reserve(mesh.nodes.size());
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    const glm::dvec3& p = mesh.nodes[i];
    for (int k = 0; k < 3; ++k) {
      if (std::abs(p[k]) <= static_cast<double>(kMaxCoordinate)) continue;
      std::ostringstream msg;
      msg << "node " << i << " has coordinate " << p[k] << ", outside +-" << kMaxCoordinate
          << " (deformcd::kMaxCoordinate), the range in which contacts do not depend on the "
             "units: give the model in other units, or nearer the origin";
      throw InputError(source, msg.str());
    }
    body.positions.emplace_back(glm::vec3(p), 1.0f);
  }
  body.velocities.assign(mesh.nodes.size(), glm::vec4(0.0f));

  // Each tetrahedron's volume, once: masses, volume forces and spring stiffnesses use it.
  std::vector<double> tet_volume;
  tet_volume.reserve(mesh.tetrahedra.size());
  for (const Tetrahedron& t : mesh.tetrahedra) {
    tet_volume.push_back(geom::signed_volume6(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]],
                                              mesh.nodes[t[3]]) /
                         6.0);
  }

  // Lumped mass: a quarter of each tetrahedron's mass to each of its nodes.
  std::vector<double> mass(mesh.nodes.size(), 0.0);
  for (std::size_t ti = 0; ti < mesh.tetrahedra.size(); ++ti) {
    const Tetrahedron& t = mesh.tetrahedra[ti];
    const double v = tet_volume[ti];
    body.volume += v;
    body.tet_rest_volume.push_back(static_cast<float>(v));
    double edges = 0.0;
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j)
        edges += glm::length(mesh.nodes[t[i]] - mesh.nodes[t[j]]);
    }
    body.tet_rest_edge.push_back(static_cast<float>(edges / 6.0));
    for (std::uint32_t n : t)
      mass[n] += 0.25 * v * options.density;
  }
  for (std::size_t i = 0; i < mass.size(); ++i) {
    if (mass[i] <= 0.0) {
      std::ostringstream msg;
      msg << "node " << i << " (0-based) belongs to no tetrahedron; a body needs every node to "
          << "have mass (remove unused nodes)";
      throw InputError(source, msg.str());
    }
  }
  floor_node_masses(mass, options.node_mass_floor);
  body.node_mass.reserve(mass.size());
  for (const double m : mass)
    body.node_mass.push_back(static_cast<float>(m));

  const std::vector<TetEdge> edges = tetrahedron_edges(mesh.tetrahedra, options.merge_shared_edges);
  for (const TetEdge& e : edges) {
    const double rest = glm::length(mesh.nodes[e.nodes[0]] - mesh.nodes[e.nodes[1]]);
    double volume = 0.0;  // of the tetrahedra this spring stands for
    for (std::uint32_t t : e.tetrahedra)
      volume += tet_volume[t];
    const double k = options.stiffness * volume / (rest * rest);
    body.springs.push_back(
        {e.nodes[0], e.nodes[1], static_cast<float>(rest), static_cast<float>(k)});
  }

  for (const Triangle& f : extract_boundary(mesh.tetrahedra, source)) {
    body.faces.push_back({f[0], f[1], f[2], 0});
  }
  update_face_normals(body);
  return body;
}

void update_face_normals(Body& body) {
  body.face_normals.resize(body.faces.size());
  for (std::size_t i = 0; i < body.faces.size(); ++i) {
    const gpu::Face& f = body.faces[i];
    const glm::vec3 a(body.positions[f.a]), b(body.positions[f.b]), c(body.positions[f.c]);
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float len = glm::length(n);
    body.face_normals[i] = len > 0.0f ? glm::vec4(n / len, 0.0f) : glm::vec4(0.0f);
  }
}

Bounds compute_bounds(const Body& body) {
  Bounds b;
  if (body.positions.empty()) return b;
  b.min = b.max = glm::dvec3(body.positions[0]);
  for (const glm::vec4& p : body.positions) {
    b.min = glm::min(b.min, glm::dvec3(p));
    b.max = glm::max(b.max, glm::dvec3(p));
  }
  return b;
}

}  // namespace deformcd
