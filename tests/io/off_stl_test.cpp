// Reading OFF and STL, and writing OFF.

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

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
// The quads 0321 4567 0154 1265 2376 3047, each fanned from its first corner.
const std::vector<Triangle> kCubeTriangles = {{0, 3, 2}, {0, 2, 1}, {4, 5, 6}, {4, 6, 7},
                                              {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},
                                              {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};

TEST(IsSurfaceFile, KnowsTheFourFormatsInAnyCase) {
  for (const char* name : {"a.off", "a.OBJ", "dir/a.Stl", "a.ply"}) {
    EXPECT_TRUE(is_surface_file(name)) << name;
  }
  for (const char* name : {"a.node", "a", "a.off.gz", "off"}) {
    EXPECT_FALSE(is_surface_file(name)) << name;
  }
}

TEST(ReadSurface, RejectsUnknownExtensions) {
  test::expect_input_error([] { (void)read_surface("mesh.xyz"); }, "mesh.xyz", 0,
                           {"unknown surface format '.xyz'"});
}

TEST(ReadOff, ReadsQuadsInFileOrderAndFanTriangulates) {
  const SurfaceMesh mesh = read_surface(data_file("cube.off"));
  EXPECT_EQ(mesh.vertices, kCubeVertices);
  EXPECT_EQ(mesh.triangles, kCubeTriangles);
}

TEST(ReadOff, AcceptsCountsOnTheHeaderLineAndColorAndNormalVariants) {
  TempDir dir;
  const std::string plain = "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const std::string colored =
      "COFF\n3 1\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1\n3 0 1 2 255 0 0\n";
  const std::string normals = "NOFF\n3 1 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
  for (const std::string& text : {plain, colored, normals}) {
    const SurfaceMesh mesh = read_surface(write_file(dir / "t.off", text));
    EXPECT_EQ(mesh.vertices, (std::vector<glm::dvec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})) << text;
    EXPECT_EQ(mesh.triangles, (std::vector<Triangle>{{0, 1, 2}})) << text;
  }
}

TEST(ReadOff, RejectsUnsupportedVariantsClearly) {
  TempDir dir;
  test::expect_input_error(
      [&] { (void)read_surface(write_file(dir / "h.off", "4OFF\n3 1 0\n0 0 0 1\n")); }, "h.off", 1,
      {"'4OFF'", "not supported"});
  test::expect_input_error([&] { (void)read_surface(write_file(dir / "b.off", "OFF BINARY\n")); },
                           "b.off", 1, {"binary OFF is not supported"});
}

TEST(WriteOff, RoundTripsExactly) {
  SurfaceMesh mesh = test::octahedron();
  mesh.vertices[0] = {1.0 + std::numeric_limits<double>::epsilon(), 1e-3 / 3.0, -0.0};
  mesh.vertices[4].z = 0.1;
  TempDir dir;
  write_off(mesh, dir / "octahedron.off");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"octahedron.off"});
  const SurfaceMesh back = read_surface(dir / "octahedron.off");
  EXPECT_EQ(back.vertices, mesh.vertices);
  EXPECT_EQ(back.triangles, mesh.triangles);
}

// The octahedron's corners as read from octahedron.stl, welded in order of first appearance.
const std::vector<glm::dvec3> kStlOctahedronVertices = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1},
                                                        {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};

std::vector<Triangle> renumbered(const std::vector<Triangle>& triangles,
                                 const std::vector<glm::dvec3>& from,
                                 const std::vector<glm::dvec3>& to) {
  std::vector<Triangle> result = triangles;
  for (Triangle& t : result) {
    for (std::uint32_t& v : t) {
      v = static_cast<std::uint32_t>(std::find(to.begin(), to.end(), from[v]) - to.begin());
    }
  }
  return result;
}

TEST(ReadStl, ReadsAsciiAndWeldsCornersInOrderOfFirstAppearance) {
  const SurfaceMesh mesh = read_surface(data_file("octahedron.stl"));
  const SurfaceMesh expected = test::octahedron();
  EXPECT_EQ(mesh.vertices, kStlOctahedronVertices);
  EXPECT_EQ(mesh.triangles,
            renumbered(expected.triangles, expected.vertices, kStlOctahedronVertices));
}

std::string binary_stl(const SurfaceMesh& mesh, std::string_view header) {
  test::ByteWriter out;
  std::string header80(header);
  header80.resize(80, ' ');
  out.text(header80).put(static_cast<std::uint32_t>(mesh.triangles.size()));
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      out.put(0.0f);
    }
    for (const std::uint32_t v : t) {
      for (int k = 0; k < 3; ++k) {
        out.put(static_cast<float>(mesh.vertices[v][k]));
      }
    }
    out.put(std::uint16_t{0});
  }
  return out.data();
}

TEST(ReadStl, ReadsBinaryWhoseHeaderStartsWithSolid) {
  TempDir dir;
  write_file(dir / "o.stl", binary_stl(test::octahedron(), "solid octahedron, but binary"));
  const SurfaceMesh mesh = read_surface(dir / "o.stl");
  const SurfaceMesh ascii = read_surface(data_file("octahedron.stl"));
  EXPECT_EQ(mesh.vertices, ascii.vertices);
  EXPECT_EQ(mesh.triangles, ascii.triangles);
}

TEST(ReadStl, WeldsOnlyExactlyEqualCornersAndTreatsSignedZerosAsEqual) {
  SurfaceMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {-0.0, -0.0, 0}, {1, 1e-7, 0}};
  mesh.triangles = {{0, 1, 2}, {2, 1, 3}, {4, 3, 5}};
  TempDir dir;
  write_file(dir / "w.stl", binary_stl(mesh, "welding"));
  const SurfaceMesh welded = read_surface(dir / "w.stl");
  // (-0, -0, 0) is the first corner again; (1, 1e-7, 0) is a new vertex.
  EXPECT_EQ(welded.vertices,
            (std::vector<glm::dvec3>{
                {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, static_cast<double>(1e-7f), 0}}));
  EXPECT_EQ(welded.triangles, (std::vector<Triangle>{{0, 1, 2}, {2, 1, 3}, {0, 3, 4}}));
}

TEST(ReadStl, RejectsTruncatedBinary) {
  TempDir dir;
  std::string data = binary_stl(test::octahedron(), "solid but binary");
  data.resize(data.size() - 7);
  write_file(dir / "cut.stl", data);
  test::expect_input_error([&] { (void)read_surface(dir / "cut.stl"); }, "cut.stl", 0,
                           {"announces 8 triangles", "truncated"});
}

}  // namespace
}  // namespace deformcd
