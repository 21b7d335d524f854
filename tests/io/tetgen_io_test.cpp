// Reading and writing TetGen files that are well formed.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "io/io_test_support.h"
#include "support/mesh_fixtures.h"

namespace deformcd {
namespace {

using test::data_file;
using test::read_text;
using test::TempDir;
using test::write_file;

const std::vector<Triangle> kCubeFaces = {{0, 4, 3}, {0, 1, 4}, {0, 3, 1}, {2, 6, 1},
                                          {2, 3, 6}, {2, 1, 3}, {5, 1, 6}, {5, 4, 1},
                                          {5, 6, 4}, {7, 3, 4}, {7, 6, 3}, {7, 4, 6}};

TEST(ReadTetgen, ReadsOneBasedFilesWithCommentsAttributesAndMarkers) {
  const TetMesh mesh = read_tetgen(data_file("cube"));
  const TetMesh expected = test::unit_cube();
  EXPECT_EQ(mesh.nodes, expected.nodes);
  EXPECT_EQ(mesh.tetrahedra, expected.tetrahedra);
  EXPECT_EQ(mesh.faces, kCubeFaces);
}

TEST(ReadTetgen, ReadsZeroBasedFilesWithoutFaceFile) {
  const TetMesh mesh = read_tetgen(data_file("tetrahedron"));
  const TetMesh expected = test::unit_tetrahedron();
  EXPECT_EQ(mesh.nodes, expected.nodes);
  EXPECT_EQ(mesh.tetrahedra, expected.tetrahedra);
  EXPECT_TRUE(mesh.faces.empty());
}

TEST(ReadTetgen, AcceptsThePathOfAnyOfItsFiles) {
  const TetMesh by_prefix = read_tetgen(data_file("cube"));
  for (const char* name : {"cube.node", "cube.ele", "cube.face"}) {
    const TetMesh mesh = read_tetgen(data_file(name));
    EXPECT_EQ(mesh.nodes, by_prefix.nodes) << name;
    EXPECT_EQ(mesh.tetrahedra, by_prefix.tetrahedra) << name;
    EXPECT_EQ(mesh.faces, by_prefix.faces) << name;
  }
}

TEST(ReadTetgen, AcceptsHeadersWithDefaultedFieldsAndPlusSigns) {
  TempDir dir;
  write_file(dir / "t.node", "4\n1 0 0 0\n2 +1 0 0\n3 0 1.0e0 0\n4 0 0 1\n");
  write_file(dir / "t.ele", "1\n1 1 2 3 4\n");
  const TetMesh mesh = read_tetgen(dir / "t");
  EXPECT_EQ(mesh.nodes, test::unit_tetrahedron().nodes);
  EXPECT_EQ(mesh.tetrahedra, test::unit_tetrahedron().tetrahedra);
}

TEST(ReadTetgen, ReorientsNegativelyOrientedFiles) {
  TempDir dir;
  write_file(dir / "t.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n");
  write_file(dir / "t.ele", "1 4 0\n0 0 1 3 2\n");
  const TetMesh mesh = read_tetgen(dir / "t");
  EXPECT_EQ(mesh.tetrahedra, test::unit_tetrahedron().tetrahedra);
}

TEST(WriteTetgen, RoundTripsExactlyAndZeroBased) {
  TetMesh mesh = test::unit_cube();
  // Awkward doubles, moved little enough to keep every tetrahedron's orientation.
  mesh.nodes[0] = {0.001, 1.0 / 300.0, -1e-300};
  mesh.nodes[6] = {1.0 + std::numeric_limits<double>::epsilon(), 0.9999999999999999, 4.0 / 3.0};
  mesh.faces = kCubeFaces;
  TempDir dir;
  write_tetgen(mesh, dir / "cube.1");  // TetGen's naming: the ".1" belongs to the prefix

  EXPECT_EQ(dir.files(), (std::vector<std::string>{"cube.1.ele", "cube.1.face", "cube.1.node"}));
  const std::string node_text = read_text(dir / "cube.1.node");
  EXPECT_EQ(node_text.rfind("# cube.1.node, written by deformcd", 0), 0u) << node_text;
  EXPECT_NE(node_text.find("\n8 3 0 0\n0 "), std::string::npos) << node_text;
  EXPECT_NE(read_text(dir / "cube.1.face").find("\n0 0 4 3 1\n"), std::string::npos);

  const TetMesh back = read_tetgen(dir / "cube.1");
  EXPECT_EQ(back.nodes, mesh.nodes);
  EXPECT_EQ(back.tetrahedra, mesh.tetrahedra);
  EXPECT_EQ(back.faces, mesh.faces);
}

TEST(WriteTetgen, WritesAnEmptyFaceFileWhenTheMeshHasNoFaces) {
  TempDir dir;
  write_file(dir / "t.face", "stale");
  write_tetgen(test::unit_tetrahedron(), dir / "t.node");
  const TetMesh back = read_tetgen(dir / "t");
  EXPECT_TRUE(back.faces.empty());
  EXPECT_EQ(back.tetrahedra, test::unit_tetrahedron().tetrahedra);
}

TEST(WriteTetgen, RejectsMeshesThatWouldNotReadBack) {
  TempDir dir;
  TetMesh bad_index = test::unit_tetrahedron();
  bad_index.tetrahedra[0][3] = 4;
  EXPECT_THROW(write_tetgen(bad_index, dir / "t"), Error);
  TetMesh bad_node = test::unit_tetrahedron();
  bad_node.nodes[1].y = std::nan("");
  EXPECT_THROW(write_tetgen(bad_node, dir / "t"), Error);
  EXPECT_TRUE(dir.files().empty());
}

}  // namespace
}  // namespace deformcd
