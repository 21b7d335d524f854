#pragma once
// The CGAL types every stage of make_models works on.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

namespace make_models {

// Exact predicates keep the self-intersection and orientation checks trustworthy; constructions
// (new vertex positions from decimation and hole fairing) are plain doubles.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

}  // namespace make_models
