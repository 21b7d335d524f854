#pragma once
/// \file body.h
/// A body: the GPU-ready arrays of one deformable object (the paper's Table 1 buffers),
/// built from a tetrahedral mesh. Plain public arrays, one per buffer.

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "deformcd/gpu_layout.h"
#include "deformcd/mesh.h"

namespace deformcd {

/// How a body is built from a tetrahedral mesh.
struct BodyOptions {
  /// Mass density (kg/m^3): node masses are lumped, a quarter of each adjacent tetrahedron's
  /// mass (raised where node_mass_floor is set above 0).
  double density = 1000.0;
  /// Young's-modulus-like stiffness (Pa). Each spring on an edge of tetrahedron t gets
  /// k = stiffness x volume(t) / rest_length^2 (summed over the tetrahedra when edges are
  /// merged), so that a body's response does not depend on how finely it is meshed.
  double stiffness = 1.0e5;
  /// false (the paper): one spring per tetrahedron edge, springs = 6 x tetrahedra.
  /// true: an edge shared by several tetrahedra becomes one spring.
  bool merge_shared_edges = false;
  /// Each node's lumped mass is raised to at least this share of the body's mean node mass,
  /// and all are then scaled so that the body's mass stays density x volume (0, the default,
  /// keeps the pure lumping; at most 1). Lumped masses of a tetrahedral mesh vary by thousands
  /// within a body, the lightest at the surface, and they set the explicit integration's stable
  /// substep: at 0.5 the paper's phase 1 runs at 4 substeps a frame instead of blowing up at
  /// 10. With the contact response it takes a quarter to a third of the iterations off; a scene
  /// with a response sets it to kResponseNodeMassFloor (0.3) unless its material says
  /// otherwise (docs/simulation-and-response.md, "Node masses").
  double node_mass_floor = 0.0;
};

/// Axis-aligned bounds of a point set.
struct Bounds {
  glm::dvec3 min{0.0};  ///< smallest x, y and z
  glm::dvec3 max{0.0};  ///< largest x, y and z
};

/// One deformable body. Indices in springs and faces are local to this body (0-based);
/// a world concatenates bodies and offsets them.
struct Body {
  std::vector<glm::vec4> positions;     ///< SSBO 0: xyz, w = 1
  std::vector<glm::vec4> velocities;    ///< SSBO 1: xyz, w = 0
  std::vector<gpu::Spring> springs;     ///< SSBO 2
  std::vector<gpu::Face> faces;         ///< SSBO 7: outward surface triangles
  std::vector<glm::vec4> face_normals;  ///< SSBO 6: unit outward normals, w = 0
  std::vector<float> node_mass;         ///< kg, lumped from the tetrahedra
  std::vector<Tetrahedron> tetrahedra;  ///< positively oriented
  std::vector<float> tet_rest_volume;   ///< m^3, per tetrahedron, at build time
  std::vector<float> tet_rest_edge;     ///< m, mean edge length per tetrahedron, at build time
  double volume = 0.0;                  ///< m^3, sum of the tetrahedra
};

/// Builds a body from a valid tetrahedral mesh (see validate_tet_mesh).
/// `source` names the mesh in error messages.
/// Throws InputError if the tetrahedra do not form a manifold solid (a face shared by more than
/// two tetrahedra) or a surface face is degenerate.
[[nodiscard]] Body build_body(const TetMesh& mesh, const BodyOptions& options = {},
                              const std::string& source = "<mesh>");

/// Recomputes face_normals from positions (unit, outward; zero for a collapsed face).
void update_face_normals(Body& body);

/// Bounds of a body's current positions.
[[nodiscard]] Bounds compute_bounds(const Body& body);

}  // namespace deformcd
