#include "deformcd/mesh_validation.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "deformcd/error.h"
#include "support/mesh_fixtures.h"

namespace deformcd {
namespace {

MeshSource source_with_lines() {
  MeshSource s;
  s.vertex_file = "cube.node";
  s.vertex_lines = {2, 3, 4, 5, 6, 7, 8, 9};
  s.element_file = "cube.ele";
  s.element_lines = {2, 3, 4, 5, 6};
  s.index_base = 1;
  return s;
}

std::string message_of(TetMesh mesh, const MeshSource& src) {
  try {
    validate_tet_mesh(mesh, src);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ValidateTetMesh, AcceptsValidCube) {
  TetMesh cube = test::unit_cube();
  EXPECT_NO_THROW(validate_tet_mesh(cube, source_with_lines()));
  EXPECT_EQ(cube.tetrahedra, test::unit_cube().tetrahedra);
}

TEST(ValidateTetMesh, ReorientsConsistentlyNegativeMesh) {
  TetMesh cube = test::unit_cube();
  for (Tetrahedron& t : cube.tetrahedra)
    std::swap(t[0], t[1]);
  validate_tet_mesh(cube, source_with_lines());
  for (const Tetrahedron& t : cube.tetrahedra) {
    const auto& n = cube.nodes;
    const double v = glm::dot(n[t[1]] - n[t[0]], glm::cross(n[t[2]] - n[t[0]], n[t[3]] - n[t[0]]));
    EXPECT_GT(v, 0.0);
  }
}

TEST(ValidateTetMesh, ReportsInvertedTetrahedronWithFileAndLine) {
  TetMesh cube = test::unit_cube();
  std::swap(cube.tetrahedra[3][0], cube.tetrahedra[3][1]);
  const std::string msg = message_of(cube, source_with_lines());
  EXPECT_NE(msg.find("cube.ele:5:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("tetrahedron 4"), std::string::npos) << msg;
  EXPECT_NE(msg.find("inverted"), std::string::npos) << msg;
}

TEST(ValidateTetMesh, ReportsZeroVolumeTetrahedron) {
  TetMesh mesh = test::unit_tetrahedron();
  mesh.nodes[3] = {0.5, 0.5, 0.0};  // flat
  const std::string msg = message_of(mesh, {"t.node", {}, "t.ele", {7}, 0});
  EXPECT_NE(msg.find("t.ele:7:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("zero volume"), std::string::npos) << msg;
}

TEST(ValidateTetMesh, DegeneracyIsScaleIndependent) {
  for (double scale : {1e-6, 1.0, 1e6}) {
    TetMesh mesh = test::unit_tetrahedron();
    for (auto& p : mesh.nodes)
      p *= scale;
    EXPECT_NO_THROW(validate_tet_mesh(mesh, {})) << "scale " << scale;
  }
}

TEST(ValidateTetMesh, ReportsNonFiniteCoordinate) {
  for (double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    TetMesh cube = test::unit_cube();
    cube.nodes[2].y = bad;
    const std::string msg = message_of(cube, source_with_lines());
    EXPECT_NE(msg.find("cube.node:4:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("vertex 3"), std::string::npos) << msg;
    EXPECT_NE(msg.find("NaN or infinite"), std::string::npos) << msg;
  }
}

TEST(ValidateTetMesh, ReportsIndexOutOfRangeAndRepeatedNode) {
  TetMesh cube = test::unit_cube();
  cube.tetrahedra[1][2] = 8;
  std::string msg = message_of(cube, source_with_lines());
  EXPECT_NE(msg.find("cube.ele:3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("out of range (valid: 1..8)"), std::string::npos) << msg;

  cube = test::unit_cube();
  cube.tetrahedra[0][3] = cube.tetrahedra[0][0];
  msg = message_of(cube, source_with_lines());
  EXPECT_NE(msg.find("repeats a vertex"), std::string::npos) << msg;
}

TEST(ValidateSurfaceMesh, ReportsDegenerateTriangle) {
  SurfaceMesh s = test::octahedron();
  s.vertices.push_back({2, 0, 0});
  s.triangles.push_back({0, 6, 0});  // repeated vertex
  EXPECT_THROW(validate_surface_mesh(s, {}), InputError);
  s.triangles.back() = {0, 1, 6};  // collinear: (1,0,0), (-1,0,0), (2,0,0)
  try {
    validate_surface_mesh(s, {"s.off", {}, "s.off", {}, 0});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 8 (0 1 6) is degenerate"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace deformcd
