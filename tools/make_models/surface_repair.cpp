#include "surface_repair.h"

#include <algorithm>
#include <iterator>
#include <string>
#include <tuple>
#include <vector>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/repair_self_intersections.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/iterator.h>

#include "deformcd/error.h"

namespace make_models {

namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

Mesh read_as_mesh(const std::filesystem::path& file) {
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(file.string(), points, polygons) || polygons.empty()) {
    throw deformcd::InputError(file.string(), "cannot read a polygon soup from this file");
  }
  // Merges duplicated points, drops duplicated and degenerate polygons, then splits
  // non-manifold vertices so that the soup becomes an orientable polygon mesh.
  PMP::repair_polygon_soup(points, polygons);
  PMP::orient_polygon_soup(points, polygons);
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  if (!CGAL::is_triangle_mesh(mesh)) PMP::triangulate_faces(mesh);
  return mesh;
}

// Fills every hole. Fairing makes the patch smooth and sampled like its surroundings; when the
// fairing system cannot be solved CGAL keeps the refined, unfaired patch (counted in
// summary.holes_unfaired). A hole that cannot be triangulated at all stays open and is reported
// by the closedness check of load_and_repair.
void fill_holes(Mesh& mesh, RepairSummary& summary) {
  std::vector<Mesh::Halfedge_index> borders;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(borders));
  for (Mesh::Halfedge_index h : borders) {
    std::vector<Mesh::Face_index> patch;
    const bool faired = std::get<0>(PMP::triangulate_refine_and_fair_hole(
        mesh, h, std::back_inserter(patch), CGAL::Emptyset_iterator()));
    if (patch.empty()) continue;
    ++summary.holes_filled;
    if (!faired) ++summary.holes_unfaired;
    summary.hole_faces_added += patch.size();
  }
}

}  // namespace

Mesh load_and_repair(const std::filesystem::path& file, RepairSummary& summary) {
  Mesh mesh = read_as_mesh(file);
  PMP::stitch_borders(mesh);

  summary.components_removed = PMP::keep_largest_connected_components(mesh, 1);
  mesh.collect_garbage();

  fill_holes(mesh, summary);

  const std::size_t faces_before = mesh.number_of_faces();
  PMP::remove_degenerate_faces(mesh);
  mesh.collect_garbage();
  // Removal collapses or flips edges: the count can only shrink.
  summary.degenerate_faces_removed =
      faces_before - std::min<std::size_t>(faces_before, mesh.number_of_faces());

  if (PMP::does_self_intersect(mesh)) {
    PMP::experimental::remove_self_intersections(mesh);
    mesh.collect_garbage();
    summary.self_intersections_repaired = true;
  }

  if (!CGAL::is_closed(mesh)) {
    throw deformcd::InputError(file.string(),
                               "still has holes after hole filling: " + describe(inspect(mesh)));
  }
  if (!PMP::is_outward_oriented(mesh)) {
    PMP::reverse_face_orientations(mesh);
    summary.reversed = true;
  }
  summary.result = inspect(mesh);
  if (!is_clean(summary.result)) {
    throw deformcd::InputError(file.string(), "cannot be repaired into a clean closed surface: " +
                                                  describe(summary.result));
  }
  return mesh;
}

}  // namespace make_models
