#include "surface_output.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <CGAL/Polygon_mesh_processing/bbox.h>

#include "deformcd/error.h"

namespace make_models {

namespace {

double snap(double x) {
  const double steps = std::round(x / kCoordinateGrid);
  return steps == 0.0 ? 0.0 : steps / 1e6;  // no "-0.000000" in the file
}

}  // namespace

void normalize_to_unit_box(Mesh& mesh) {
  const CGAL::Bbox_3 box = CGAL::Polygon_mesh_processing::bbox(mesh);
  const double cx = 0.5 * (box.xmin() + box.xmax());
  const double cy = 0.5 * (box.ymin() + box.ymax());
  const double cz = 0.5 * (box.zmin() + box.zmax());
  const double extent =
      std::max({box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin()});
  if (!(extent > 0.0)) throw deformcd::Error("normalize: the surface has an empty bounding box");
  for (Mesh::Vertex_index v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    mesh.point(v) = Point(snap((p.x() - cx) / extent), snap((p.y() - cy) / extent),
                          snap((p.z() - cz) / extent));
  }
}

void write_off(const Mesh& mesh, const std::filesystem::path& file) {
  if (mesh.has_garbage()) throw deformcd::Error("write_off: collect_garbage() first");
  std::ofstream out(file);
  if (!out) throw deformcd::Error(file.string() + ": cannot open for writing");
  out << "OFF\n" << mesh.number_of_vertices() << ' ' << mesh.number_of_faces() << " 0\n";
  char line[128];
  for (Mesh::Vertex_index v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    std::snprintf(line, sizeof line, "%.6f %.6f %.6f\n", p.x(), p.y(), p.z());
    out << line;
  }
  for (Mesh::Face_index f : mesh.faces()) {
    out << '3';
    for (Mesh::Vertex_index v : vertices_around_face(mesh.halfedge(f), mesh)) {
      out << ' ' << static_cast<std::size_t>(v);
    }
    out << '\n';
  }
  out.close();
  if (!out) throw deformcd::Error(file.string() + ": write failed");
}

}  // namespace make_models
