// Bad TetGen input: every error names the file, the line where there is one, and what is wrong.

#include <gtest/gtest.h>

#include "deformcd/io.h"
#include "io/io_test_support.h"

namespace deformcd {
namespace {

using test::expect_input_error;
using test::TempDir;
using test::write_file;

// A unit tetrahedron plus one more node (5), 1-based, as the base of the bad variants.
constexpr const char* kNode = "5 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n";
constexpr const char* kEle = "2 4 0\n1 1 2 3 4\n2 2 5 3 4\n";

class TetgenErrors : public ::testing::Test {
 protected:
  // Writes bad.node and bad.ele (and bad.face if given) and reads them back.
  void read(const std::string& node, const std::string& ele, const char* face = nullptr) {
    write_file(dir_ / "bad.node", node);
    write_file(dir_ / "bad.ele", ele);
    if (face) write_file(dir_ / "bad.face", face);
    (void)read_tetgen(dir_ / "bad");
  }
  TempDir dir_;
};

TEST_F(TetgenErrors, TheBaseFilesAreValid) {
  EXPECT_NO_THROW(read(kNode, kEle));
}

TEST_F(TetgenErrors, TruncatedNodeFile) {
  expect_input_error([&] { read("6 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n", kEle); },
                     "bad.node", 5, {"expected 6 nodes, file ends after 4"});
}

TEST_F(TetgenErrors, TruncatedEleFileWithTrailingComment) {
  expect_input_error([&] { read(kNode, "3 4 0\n1 1 2 3 4\n2 2 5 3 4\n# the end\n"); }, "bad.ele", 4,
                     {"expected 3 tetrahedra, file ends after 2"});
}

TEST_F(TetgenErrors, WrongCountOfFieldsOnAnElementLine) {
  expect_input_error([&] { read(kNode, "2 4 0\n1 1 2 3 4\n2 2 5\n"); }, "bad.ele", 3,
                     {"expected 5 integers (index and 4 nodes), found 3"});
}

TEST_F(TetgenErrors, TrailingGarbageOnANodeLine) {
  expect_input_error(
      [&] { read("5 3 0 0\n1 0 0 0\n2 1 0 0 garbage\n3 0 1 0\n4 0 0 1\n5 1 1 1\n", kEle); },
      "bad.node", 3, {"expected 4 numbers (index and 3 coordinates), found 5"});
}

TEST_F(TetgenErrors, AttributesAndMarkersCountInTheExpectedFields) {
  expect_input_error([&] { read("5 3 1 1\n1 0 0 0 7\n", kEle); }, "bad.node", 2,
                     {"expected 6 numbers (index, 3 coordinates, 1 attribute and a boundary "
                      "marker), found 5"});
}

TEST_F(TetgenErrors, MoreRecordsThanDeclared) {
  expect_input_error([&] { read(kNode, "1 4 0\n1 1 2 3 4\n2 2 5 3 4\n"); }, "bad.ele", 3,
                     {"unexpected content after the 1 declared tetrahedron"});
}

TEST_F(TetgenErrors, NonNumericCoordinate) {
  expect_input_error(
      [&] { read("5 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1.2.3 0\n4 0 0 1\n5 1 1 1\n", kEle); }, "bad.node",
      4, {"'1.2.3' is not a number"});
}

TEST_F(TetgenErrors, NonIntegerNodeIndexInElement) {
  expect_input_error([&] { read(kNode, "2 4 0\n1 1 2 3 4\n2 2 5.0 3 4\n"); }, "bad.ele", 3,
                     {"'5.0' is not an integer"});
}

TEST_F(TetgenErrors, NumbersOutOfRange) {
  expect_input_error(
      [&] { read("5 3 0 0\n1 0 0 0\n2 1e999 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n", kEle); }, "bad.node",
      3, {"'1e999' is out of range"});
  expect_input_error([&] { read(kNode, "2 4 0\n1 1 2 3 4\n2 2 99999999999999999999 3 4\n"); },
                     "bad.ele", 3, {"'99999999999999999999' is out of range"});
}

TEST_F(TetgenErrors, NodeIndexOutOfRange) {
  expect_input_error([&] { read(kNode, "2 4 0\n1 1 2 3 4\n2 2 9999 3 4\n"); }, "bad.ele", 3,
                     {"tetrahedron 2 refers to node 9999, out of range (valid: 1..5)"});
  expect_input_error([&] { read(kNode, "2 4 0\n1 1 2 3 4\n2 2 0 3 4\n"); }, "bad.ele", 3,
                     {"refers to node 0, out of range (valid: 1..5)"});
}

TEST_F(TetgenErrors, FaceIndexOutOfRangeNamesTheFaceFile) {
  expect_input_error([&] { read(kNode, kEle, "1 0\n1 1 2 6\n"); }, "bad.face", 2,
                     {"face 1 refers to node 6, out of range (valid: 1..5)"});
}

TEST_F(TetgenErrors, NodeIndicesMustBeConsecutive) {
  expect_input_error([&] { read("5 3 0 0\n1 0 0 0\n2 1 0 0\n4 0 1 0\n5 0 0 1\n6 1 1 1\n", kEle); },
                     "bad.node", 4, {"expected node index 3", "found 4"});
  expect_input_error([&] { read("1 3 0 0\n5 0 0 0\n", kEle); }, "bad.node", 2,
                     {"first node's index must be 0 or 1, found 5"});
}

TEST_F(TetgenErrors, NanAndInfCoordinates) {
  expect_input_error(
      [&] { read("5 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 nan 0\n4 0 0 1\n5 1 1 1\n", kEle); }, "bad.node",
      4, {"vertex 3", "NaN or infinite"});
  expect_input_error(
      [&] { read("5 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 -inf\n5 1 1 1\n", kEle); }, "bad.node",
      5, {"vertex 4", "NaN or infinite"});
}

TEST_F(TetgenErrors, ZeroVolumeTetrahedron) {
  // Node 5 moved into the plane of nodes 2, 3, 4.
  expect_input_error(
      [&] { read("5 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 0.5 0.25 0.25\n", kEle); },
      "bad.ele", 3, {"tetrahedron 2", "degenerate (zero volume)"});
}

TEST_F(TetgenErrors, InvertedTetrahedron) {
  expect_input_error([&] { read(kNode, "3 4 0\n1 1 2 3 4\n2 2 5 3 4\n3 2 3 5 4\n"); }, "bad.ele", 4,
                     {"tetrahedron 3", "inverted"});
}

TEST_F(TetgenErrors, RepeatedNode) {
  expect_input_error([&] { read(kNode, "2 4 0\n1 1 2 3 4\n2 2 5 3 2\n"); }, "bad.ele", 3,
                     {"tetrahedron 2 repeats node 2"});
}

TEST_F(TetgenErrors, DimensionTwo) {
  expect_input_error([&] { read("3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n", kEle); }, "bad.node", 1,
                     {"dimension is 2", "only 3"});
}

TEST_F(TetgenErrors, SecondOrderTetrahedraAreRejected) {
  expect_input_error([&] { read(kNode, "1 10 0\n1 1 2 3 4 5 6 7 8 9 10\n"); }, "bad.ele", 1,
                     {"second-order", "not supported"});
}

TEST_F(TetgenErrors, EmptyFile) {
  expect_input_error([&] { read("# only a comment\n\n", kEle); }, "bad.node", 2, {"no header"});
}

TEST_F(TetgenErrors, MissingFilesAreNamed) {
  expect_input_error([&] { (void)read_tetgen(dir_ / "nothing"); }, "nothing.node", 0,
                     {"cannot open", "No such file"});
  write_file(dir_ / "only.node", kNode);
  expect_input_error([&] { (void)read_tetgen(dir_ / "only"); }, "only.ele", 0, {"cannot open"});
}

}  // namespace
}  // namespace deformcd
