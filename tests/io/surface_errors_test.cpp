// Bad surface input: every error names the file, the line where there is one, and what is wrong.

#include <gtest/gtest.h>

#include "deformcd/io.h"
#include "io/io_test_support.h"

namespace deformcd {
namespace {

using test::expect_input_error;
using test::TempDir;
using test::write_file;

class SurfaceErrors : public ::testing::Test {
 protected:
  // Writes `text` to `name` and reads it as a surface, expecting an error at `line`.
  std::string expect_error(const std::string& name, const std::string& text, std::size_t line,
                           std::initializer_list<std::string_view> keywords) {
    const auto file = write_file(dir_ / name, text);
    return expect_input_error([&] { (void)read_surface(file); }, name, line, keywords);
  }
  TempDir dir_;
};

constexpr const char* kTriangleOff = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

TEST_F(SurfaceErrors, TheBaseFileIsValid) {
  EXPECT_NO_THROW((void)read_surface(write_file(dir_ / "ok.off", kTriangleOff)));
}

TEST_F(SurfaceErrors, OffTruncated) {
  expect_error("t.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", 4,
               {"expected 3 vertices, file ends after 2"});
  expect_error("f.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 6,
               {"expected 2 faces, file ends after 1"});
}

TEST_F(SurfaceErrors, OffWrongCounts) {
  expect_error("c.off", "OFF\n3\n", 2, {"expected the counts", "found 1 values"});
  expect_error("v.off", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", 4,
               {"expected 3 coordinates for vertex 1, found 2"});
  expect_error("p.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", 6,
               {"face 0 declares 4 vertices"});
  expect_error("e.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", 7,
               {"unexpected content after the 1 declared faces"});
}

TEST_F(SurfaceErrors, OffNonNumericToken) {
  expect_error("n.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1e 0\n3 0 1 2\n", 5, {"'1e' is not a number"});
  expect_error("i.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 one 2\n", 6,
               {"'one' is not an integer"});
}

TEST_F(SurfaceErrors, OffIndexOutOfRange) {
  expect_error("r.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", 6,
               {"face 0 refers to vertex 3, out of range (valid: 0..2)"});
  expect_error("m.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", 6,
               {"refers to vertex -1, out of range"});
}

TEST_F(SurfaceErrors, NanAndInfCoordinates) {
  expect_error("nan.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 NaN 0\n3 0 1 2\n", 5,
               {"vertex 2", "NaN or infinite"});
  expect_error("inf.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n", 2,
               {"vertex 2", "NaN or infinite"});
  expect_error("inf.stl",
               "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
               "vertex 0 -infinity 0\nendloop\nendfacet\nendsolid s\n",
               6, {"NaN or infinite"});
}

TEST_F(SurfaceErrors, DegenerateTriangle) {
  expect_error("d.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n2 0 0\n3 0 1 2\n3 0 1 3\n", 8,
               {"triangle 1 (0 1 3)", "degenerate (zero area)"});
  expect_error("d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n", 6,
               {"triangle 2 (1 2 4)", "degenerate (zero area)"});
  expect_error("r.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n", 6, {"repeats a vertex"});
}

TEST_F(SurfaceErrors, MissingFilesAreNamed) {
  for (const char* name : {"none.off", "none.obj", "none.stl", "none.ply"}) {
    expect_input_error([&] { (void)read_surface(dir_ / name); }, name, 0, {"cannot open"});
  }
}

TEST_F(SurfaceErrors, ObjNonNumericAndMissingCoordinates) {
  expect_error("n.obj", "v 0 0 0\nv 1 0 abc\nv 0 1 0\nf 1 2 3\n", 2, {"'abc' is not a number"});
  expect_error("m.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", 2,
               {"expected 3 coordinates after 'v'", "found 2"});
}

TEST_F(SurfaceErrors, ObjIndexOutOfRange) {
  expect_error("p.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", 4,
               {"face 1 refers to vertex 9, out of range (valid: 1..3)"});
  expect_error("n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf -1 -2 -4\n", 5,
               {"face 2 refers to vertex -4, but only 3 vertices precede it"});
  expect_error("z.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4, {"vertex 0", "start at 1"});
}

TEST_F(SurfaceErrors, ObjMalformedFaces) {
  expect_error("x.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2x 3\n", 4,
               {"'2x' is not a vertex reference"});
  expect_error("s.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", 4,
               {"face 1 has 2 corners; a face needs at least 3"});
  expect_error("n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2// 3\n", 4,
               {"'2//' is not a vertex reference"});
  // Accepted by our scan (we leave texture indices to tinyobjloader), refused by tinyobjloader:
  // its message comes through with the file and its line.
  expect_error("e.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1/0 2/0 3/0\n", 5,
               {"tinyobjloader", "`f' line"});
}

TEST_F(SurfaceErrors, StlAsciiMalformed) {
  expect_error("k.stl",
               "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n", 6,
               {"expected 'vertex <x> <y> <z>', found 'endloop'"});
  expect_error("t.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", 4,
               {"file ends"});
  expect_error("n.stl",
               "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
               "vertex 0 1 0 0\nendloop\nendfacet\nendsolid\n",
               6, {"expected 'vertex <x> <y> <z>'"});
  expect_error("x.stl", "not an stl", 0, {"neither ASCII STL", "nor binary STL"});
}

TEST_F(SurfaceErrors, PlyHeaderAndBodyErrors) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  expect_error("ok.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", 13,
               {"face 0 refers to vertex 5, out of range (valid: 0..2)"});
  expect_error("n.ply", header + "0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n", 11, {"'x' is not a number"});
  expect_error("c.ply", header + "0 0 0\n1 0 0 7\n0 1 0\n3 0 1 2\n", 11,
               {"vertex 1 has 4 values, its properties declare 3"});
  expect_error("t.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty fluffy x\n", 4,
               {"unknown property type 'fluffy'"});
  expect_error("f.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nend_header\n",
               0, {"no 'face' element"});
}

}  // namespace
}  // namespace deformcd
