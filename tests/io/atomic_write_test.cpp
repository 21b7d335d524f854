// Writers leave no file behind when they fail.

#include <gtest/gtest.h>

#include <filesystem>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "io/atomic_file.h"
#include "io_test_support.h"
#include "support/mesh_fixtures.h"

namespace deformcd {
namespace {

using test::TempDir;

TEST(AtomicFile, RemovesItsTemporaryWhenNotCommitted) {
  TempDir dir;
  {
    io::AtomicFile file(dir / "a.txt");
    file.write("contents");
    EXPECT_TRUE(std::filesystem::exists(file.temporary()));
    EXPECT_EQ(file.temporary().parent_path(), dir.path());
  }
  EXPECT_TRUE(dir.files().empty());
}

TEST(AtomicFile, CommitReplacesTheTarget) {
  TempDir dir;
  test::write_file(dir / "a.txt", "old");
  io::AtomicFile file(dir / "a.txt");
  file.write("new");
  file.commit();
  EXPECT_EQ(test::read_text(dir / "a.txt"), "new");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"a.txt"});
}

TEST(WriteTetgen, IntoAMissingDirectoryThrowsAndWritesNothing) {
  TempDir dir;
  EXPECT_THROW(write_tetgen(test::unit_cube(), dir / "missing" / "cube"), Error);
  EXPECT_TRUE(dir.files().empty());
}

TEST(WriteTetgen, FailingAfterSomeFilesWereWrittenLeavesNone) {
  // The .face target is a directory: the .node and .ele temporaries are written by then, and
  // must be neither renamed into place nor left behind.
  TempDir dir;
  std::filesystem::create_directory(dir / "cube.face");
  try {
    write_tetgen(test::unit_cube(), dir / "cube");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cube.face"), std::string::npos) << e.what();
  }
  EXPECT_EQ(dir.files(), std::vector<std::string>{"cube.face"});
}

TEST(WriteOff, IntoAMissingDirectoryThrowsAndWritesNothing) {
  TempDir dir;
  try {
    write_off(test::octahedron(), dir / "missing" / "o.off");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("o.off"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(dir.files().empty());
}

}  // namespace
}  // namespace deformcd
