#include "surface_decimation.h"

#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_placement.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include "deformcd/error.h"

namespace make_models {

namespace SMS = CGAL::Surface_mesh_simplification;

CollapsePolicy parse_collapse_policy(const std::string& name) {
  if (name == "lt") return CollapsePolicy::lindstrom_turk;
  if (name == "gh") return CollapsePolicy::garland_heckbert;
  throw deformcd::Error("unknown collapse policy '" + name + "' (expected lt or gh)");
}

std::size_t decimate(Mesh& mesh, std::size_t target_faces, CollapsePolicy policy) {
  // A closed triangle mesh has E = 3F/2 and CGAL's stop predicate counts edges; it stops as
  // soon as fewer than the threshold remain, hence the +1.
  const SMS::Count_stop_predicate<Mesh> stop(target_faces * 3 / 2 + 1);
  int edges_removed = 0;
  if (policy == CollapsePolicy::lindstrom_turk) {
    const SMS::Bounded_normal_change_placement<SMS::LindstromTurk_placement<Mesh>> placement;
    edges_removed = SMS::edge_collapse(
        mesh, stop,
        CGAL::parameters::get_cost(SMS::LindstromTurk_cost<Mesh>()).get_placement(placement));
  } else {
    using Policies = SMS::GarlandHeckbert_plane_policies<Mesh, Kernel>;
    Policies policies(mesh);
    const SMS::Bounded_normal_change_placement<Policies::Get_placement> placement(
        policies.get_placement());
    edges_removed = SMS::edge_collapse(
        mesh, stop, CGAL::parameters::get_cost(policies.get_cost()).get_placement(placement));
  }
  mesh.collect_garbage();
  return static_cast<std::size_t>(edges_removed);
}

}  // namespace make_models
