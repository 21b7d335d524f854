// Reading PLY (ASCII and binary, both endiannesses) and OBJ.

#include <gtest/gtest.h>

#include <cstdint>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "io/byte_writer.h"
#include "io/io_test_support.h"
#include "support/mesh_fixtures.h"

namespace deformcd {
namespace {

using test::data_file;
using test::TempDir;
using test::write_file;

const std::vector<glm::dvec3> kCubeVertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                               {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
const std::vector<Triangle> kCubeTriangles = {{0, 3, 2}, {0, 2, 1}, {4, 5, 6}, {4, 6, 7},
                                              {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},
                                              {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};

TEST(ReadPly, ReadsAsciiSkippingOtherPropertiesAndElements) {
  const SurfaceMesh mesh = read_surface(data_file("cube.ply"));
  EXPECT_EQ(mesh.vertices, kCubeVertices);
  EXPECT_EQ(mesh.triangles, kCubeTriangles);
}

// The octahedron as binary PLY, with a property before x, doubles for y, a list among the
// vertex properties, ushort counts and int indices, a float after the list, and an extra
// element before and after.
std::string binary_ply(bool big_endian) {
  const SurfaceMesh octahedron = test::octahedron();
  test::ByteWriter out(big_endian);
  out.text(std::string("ply\nformat ") +
           (big_endian ? "binary_big_endian" : "binary_little_endian") + " 1.0\n" +
           "comment extra properties and elements\n"
           "element material 1\nproperty list uchar float coefficients\n"
           "element vertex 6\nproperty uchar red\nproperty float x\nproperty double y\n"
           "property list uchar short tags\nproperty int16 z\n"
           "element face 8\nproperty list ushort int vertex_indices\nproperty float quality\n"
           "element note 1\nproperty uint32 id\n"
           "end_header\n");
  out.put(std::uint8_t{2}).put(0.5f).put(0.25f);
  for (const glm::dvec3& p : octahedron.vertices) {
    out.put(std::uint8_t{200}).put(static_cast<float>(p.x)).put(p.y);
    out.put(std::uint8_t{1}).put(std::int16_t{-3});
    out.put(static_cast<std::int16_t>(p.z));
  }
  for (const Triangle& t : octahedron.triangles) {
    out.put(std::uint16_t{3});
    for (const std::uint32_t v : t) {
      out.put(static_cast<std::int32_t>(v));
    }
    out.put(1.0f);
  }
  out.put(std::uint32_t{42});
  return out.data();
}

TEST(ReadPly, ReadsBinaryBigAndLittleEndian) {
  TempDir dir;
  for (const bool big_endian : {true, false}) {
    write_file(dir / "o.ply", binary_ply(big_endian));
    const SurfaceMesh mesh = read_surface(dir / "o.ply");
    EXPECT_EQ(mesh.vertices, test::octahedron().vertices) << "big endian: " << big_endian;
    EXPECT_EQ(mesh.triangles, test::octahedron().triangles) << "big endian: " << big_endian;
  }
}

TEST(ReadPly, DetectsTruncatedBinary) {
  TempDir dir;
  std::string data = binary_ply(true);
  data.resize(data.size() - 4 - 2 * 18);  // the note and 2 of the 8 faces (18 bytes each)
  write_file(dir / "cut.ply", data);
  test::expect_input_error([&] { (void)read_surface(dir / "cut.ply"); }, "cut.ply", 0,
                           {"ends inside face 6", "declares 8 face elements"});
}

TEST(ReadPly, DetectsTruncatedAscii) {
  TempDir dir;
  std::string text = test::read_text(data_file("cube.ply"));
  text.resize(text.find("7 4 2 3 7 6"));
  write_file(dir / "cut.ply", text);
  test::expect_input_error([&] { (void)read_surface(dir / "cut.ply"); }, "cut.ply", 29,
                           {"expected 6 face elements, file ends after 4"});
}

TEST(ReadObj, ReadsQuadsNegativeIndicesAndGroupsInFileOrder) {
  const SurfaceMesh mesh = read_surface(data_file("cube.obj"));
  EXPECT_EQ(mesh.vertices, kCubeVertices);
  // The same quads as cube.off, with the same first corners.
  EXPECT_EQ(mesh.triangles, kCubeTriangles);
}

TEST(ReadObj, KeepsFullDoublePrecision) {
  TempDir dir;
  write_file(dir / "p.obj", "v 0.1 0.2 0.30000000000000004\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const SurfaceMesh mesh = read_surface(dir / "p.obj");
  EXPECT_EQ(mesh.vertices[0], glm::dvec3(0.1, 0.2, 0.30000000000000004));
}

}  // namespace
}  // namespace deformcd
