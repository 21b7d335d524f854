#include "surface_checks.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>

#include "deformcd/error.h"

namespace make_models {

namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

double smallest_angle_degrees(const Mesh& mesh) {
  double smallest = 180.0;
  for (Mesh::Face_index f : mesh.faces()) {
    std::vector<Point> p;
    for (Mesh::Vertex_index v : vertices_around_face(mesh.halfedge(f), mesh)) {
      p.push_back(mesh.point(v));
    }
    for (std::size_t i = 0; i < 3; ++i) {
      const Kernel::Vector_3 a = p[(i + 1) % 3] - p[i];
      const Kernel::Vector_3 b = p[(i + 2) % 3] - p[i];
      const double norms = std::sqrt(a.squared_length() * b.squared_length());
      if (norms == 0.0) return 0.0;
      const double c = std::clamp((a * b) / norms, -1.0, 1.0);
      smallest = std::min(smallest, std::acos(c) * 180.0 / std::numbers::pi);
    }
  }
  return smallest;
}

}  // namespace

SurfaceReport inspect(const Mesh& mesh) {
  SurfaceReport r;
  r.vertices = mesh.number_of_vertices();
  r.faces = mesh.number_of_faces();
  for (Mesh::Edge_index e : mesh.edges()) {
    if (mesh.is_border(e)) ++r.border_edges;
  }
  // An external map: a const mesh cannot hold a face property.
  std::vector<std::size_t> component(mesh.num_faces(), 0);
  r.components = PMP::connected_components(mesh, CGAL::make_property_map(component));
  for (Mesh::Vertex_index v : mesh.vertices()) {
    if (PMP::is_non_manifold_vertex(v, mesh)) ++r.non_manifold_vertices;
  }
  for (Mesh::Face_index f : mesh.faces()) {
    if (PMP::is_degenerate_triangle_face(f, mesh)) ++r.degenerate_faces;
  }
  r.self_intersecting = PMP::does_self_intersect(mesh);
  if (r.border_edges == 0 && r.components == 1 && r.non_manifold_vertices == 0) {
    r.outward = PMP::is_outward_oriented(mesh);
  }
  const long euler = static_cast<long>(r.vertices) - static_cast<long>(mesh.number_of_edges()) +
                     static_cast<long>(r.faces);
  r.genus = (2 - euler) / 2;
  r.min_angle_degrees = smallest_angle_degrees(mesh);
  return r;
}

bool is_clean(const SurfaceReport& r) {
  return r.border_edges == 0 && r.components == 1 && r.non_manifold_vertices == 0 &&
         r.degenerate_faces == 0 && !r.self_intersecting && r.outward;
}

std::string describe(const SurfaceReport& r) {
  std::ostringstream s;
  s << "V=" << r.vertices << " F=" << r.faces << " genus=" << r.genus
    << " components=" << r.components << " min_angle=" << r.min_angle_degrees << "deg";
  if (r.border_edges != 0) s << " [" << r.border_edges << " border edges]";
  if (r.non_manifold_vertices != 0)
    s << " [" << r.non_manifold_vertices << " non-manifold vertices]";
  if (r.degenerate_faces != 0) s << " [" << r.degenerate_faces << " degenerate faces]";
  if (r.self_intersecting) s << " [self-intersecting]";
  if (r.border_edges == 0 && r.components == 1 && !r.outward) s << " [inward-oriented]";
  return s.str();
}

void require_clean(const Mesh& mesh, const std::string& stage) {
  const SurfaceReport r = inspect(mesh);
  if (!is_clean(r)) throw deformcd::Error(stage + ": surface not clean: " + describe(r));
}

}  // namespace make_models
