// Counts declared in headers are checked against what the file can hold before anything is
// allocated for them, and the TetGen files against each other: a corrupt count fails at once
// with the file, the header's line and what cannot fit, never with an allocation of the
// count's size. (The fuzz targets check the same with libFuzzer's -malloc_limit_mb=64.)

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <string>

#include "deformcd/io.h"
#include "io/byte_writer.h"
#include "io/io_test_support.h"

namespace deformcd {
namespace {

using test::ByteWriter;
using test::expect_input_error;
using test::TempDir;
using test::write_file;

// A unit tetrahedron plus one more node (5), 1-based, and two tetrahedra.
constexpr const char* kNode = "5 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n";
constexpr const char* kEle = "2 4 0\n1 1 2 3 4\n2 2 5 3 4\n";

class DeclaredCounts : public ::testing::Test {
 protected:
  void read_tetgen_files(const std::string& node, const std::string& ele,
                         const char* face = nullptr) {
    write_file(dir_ / "bad.node", node);
    write_file(dir_ / "bad.ele", ele);
    if (face) write_file(dir_ / "bad.face", face);
    (void)read_tetgen(dir_ / "bad");
  }
  std::string surface_error(const std::string& name, const std::string& data, std::size_t line,
                            std::initializer_list<std::string_view> keywords) {
    write_file(dir_ / name, data);
    return expect_input_error([&] { (void)read_surface(dir_ / name); }, name, line, keywords);
  }
  TempDir dir_;
};

TEST_F(DeclaredCounts, TetgenNodeCountBeyondTheFile) {
  expect_input_error([&] { read_tetgen_files("4294967295 3 0 0\n1 0 0 0\n", kEle); }, "bad.node", 1,
                     {"declares 4294967295 nodes, but the 8 bytes after this line hold at most 4 "
                      "lines",
                      "wrong count or a truncated file"});
}

TEST_F(DeclaredCounts, TetgenElementCountBeyondTheFile) {
  expect_input_error([&] { read_tetgen_files(kNode, "100000 4 0\n1 1 2 3 4\n"); }, "bad.ele", 1,
                     {"declares 100000 tetrahedra, but the 10 bytes after this line hold at most "
                      "5 lines"});
  // Comments and blank lines after the header do not hide it.
  expect_input_error([&] { read_tetgen_files(kNode, "# c\n100 4 0\n\n# comment\n1 1 2 3 4\n"); },
                     "bad.ele", 2, {"declares 100 tetrahedra", "hold at most 11 lines"});
}

TEST_F(DeclaredCounts, AFewMissingRecordsAreReportedWhereTheFileEnds) {
  // Within what the bytes could hold: the record loop reports the line where the file ends.
  expect_input_error([&] { read_tetgen_files(kNode, "3 4 0\n1 1 2 3 4\n2 2 5 3 4\n"); }, "bad.ele",
                     3, {"expected 3 tetrahedra, file ends after 2"});
}

TEST_F(DeclaredCounts, TetgenFaceCountBeyondWhatTheTetrahedraHave) {
  // 2 tetrahedra have 8 faces at most, whatever the .face file's size.
  std::string face = "9 0\n";
  for (int i = 1; i <= 9; ++i) {
    face += std::to_string(i) + " 1 2 3\n";
  }
  const std::string what =
      expect_input_error([&] { read_tetgen_files(kNode, kEle, face.c_str()); }, "bad.face", 1,
                         {"declares 9 faces, but the 2 tetrahedra of", "have only 8 faces",
                          "does not belong to this .ele"});
  EXPECT_NE(what.find("bad.ele"), std::string::npos) << what;
}

TEST_F(DeclaredCounts, TetgenFaceCountBeyondTheFile) {
  expect_input_error([&] { read_tetgen_files(kNode, kEle, "8 0\n1 1 2 3\n"); }, "bad.face", 1,
                     {"declares 8 faces, but the 8 bytes after this line hold at most 4 lines"});
}

TEST_F(DeclaredCounts, TetgenFilesOfDifferentMeshes) {
  // A .node with fewer nodes than the .ele uses.
  expect_input_error(
      [&] { read_tetgen_files("4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n", kEle); }, "bad.ele",
      3, {"tetrahedron 2 refers to node 5, out of range (valid: 1..4)"});
  // A 0-based .ele with a 1-based .node.
  expect_input_error([&] { read_tetgen_files(kNode, "1 4 0\n0 0 1 2 3\n"); }, "bad.ele", 2,
                     {"expected tetrahedron index 1", "as the nodes'", "found 0"});
  // A 0-based .face with a 1-based .node.
  expect_input_error([&] { read_tetgen_files(kNode, kEle, "1 0\n0 1 2 3\n"); }, "bad.face", 2,
                     {"expected face index 1", "found 0"});
}

TEST_F(DeclaredCounts, OffCountsBeyondTheFile) {
  surface_error("big.off", "OFF\n1000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 2,
                {"declares 1000000001 vertices and faces, but the 26 bytes after this line hold "
                 "at most 13 lines"});
  surface_error("big_faces.off", "OFF 3 4294967295\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 1,
                {"declares 4294967298 vertices and faces"});
}

TEST_F(DeclaredCounts, PlyAsciiElementCountBeyondTheFile) {
  surface_error("big.ply",
                "ply\nformat ascii 1.0\nelement vertex 9223372036854775807\nproperty float x\n"
                "property float y\nproperty float z\nelement face 1\n"
                "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                "3 0 1 2\n",
                3,
                {"declares 9223372036854775807 'vertex' elements (one per line), but the body "
                 "after the header has 26 bytes"});
}

TEST_F(DeclaredCounts, PlyBinaryElementCountsBeyondTheFile) {
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face ";
  ByteWriter body;
  for (const float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) {
    body.put(v);
  }
  body.put(std::uint8_t{3}).put(std::int32_t{0}).put(std::int32_t{1}).put(std::int32_t{2});
  const std::string tail = "\nproperty list uchar int vertex_indices\nend_header\n";
  ASSERT_NO_THROW(
      (void)read_surface(write_file(dir_ / "ok.ply", header + "1" + tail + body.data())));
  // The 3 vertices take 36 of the 49 bytes; each face at least its 1-byte count.
  surface_error("faces.ply", header + "14" + tail + body.data(), 7,
                {"declares 14 'face' elements (at least 1 byte each), but the body after the "
                 "header has 49 bytes, 36 of them for the elements before"});
  surface_error("huge.ply", header + "9223372036854775807" + tail + body.data(), 7,
                {"declares 9223372036854775807 'face' elements"});
}

TEST_F(DeclaredCounts, PlyElementsWithoutPropertiesTakeNoBytes) {
  // Nothing is read or reserved for them, so any count is harmless.
  const std::string text =
      "ply\nformat ascii 1.0\nelement nothing 9223372036854775807\nelement vertex 3\n"
      "property float x\nproperty float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(read_surface(write_file(dir_ / "n.ply", text)).triangles.size(), 1u);
}

TEST_F(DeclaredCounts, StlBinaryTriangleCountAgainstTheFileSize) {
  // The largest count: 84 + 50 x 4294967295 bytes does not overflow in the message.
  ByteWriter stl;
  stl.text(std::string(80, ' ')).put(std::uint32_t{0xffffffff});
  for (int i = 0; i < 25; ++i) {
    stl.put(std::uint16_t{0});
  }
  surface_error("huge.stl", stl.data(), 0,
                {"announces 4294967295 triangles (214748364834 bytes), but the file has 134 "
                 "bytes"});
}

TEST_F(DeclaredCounts, OnlyRegularFilesAreRead) {
  // A FIFO would block (and /dev/zero never end): refused before opening.
  ASSERT_EQ(::mkfifo((dir_ / "fifo.off").c_str(), 0600), 0);
  expect_input_error([&] { (void)read_surface(dir_ / "fifo.off"); }, "fifo.off", 0,
                     {"is not a regular file"});
  ASSERT_EQ(::mkfifo((dir_ / "fifo.node").c_str(), 0600), 0);
  expect_input_error([&] { (void)read_tetgen(dir_ / "fifo"); }, "fifo.node", 0,
                     {"is not a regular file"});
  // A link to a file is read.
  write_file(dir_ / "t.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  std::filesystem::create_symlink(dir_ / "t.off", dir_ / "link.off");
  EXPECT_EQ(read_surface(dir_ / "link.off").triangles.size(), 1u);
}

}  // namespace
}  // namespace deformcd
