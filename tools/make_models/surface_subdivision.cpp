#include "surface_subdivision.h"

#include <CGAL/subdivision_method_3.h>

namespace make_models {

int subdivide_to_at_least(Mesh& mesh, std::size_t min_faces) {
  // Loop: each pass is x4 and converges to a smooth surface close to the source on meshes this
  // dense (vertices move by a fraction of an edge length); decimation then removes the surplus
  // where the surface is flattest, as it does for the shipped models.
  int passes = 0;
  while (mesh.number_of_faces() < min_faces) {
    CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(1));
    ++passes;
  }
  return passes;
}

}  // namespace make_models
