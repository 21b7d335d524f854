// Writers leave no file behind when they fail.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "io/atomic_file.h"
#include "io/io_test_support.h"
#include "support/mesh_fixtures.h"

namespace deformcd {
namespace {

using test::TempDir;

TEST(AtomicFile, RemovesItsTemporaryWhenNotCommitted) {
  TempDir dir;
  {
    io::AtomicFile file(dir / "a.txt");
    file.write("contents");
    EXPECT_TRUE(file.is_open());
    if (!file.named_temporary().empty()) {  // a file system without O_TMPFILE
      EXPECT_TRUE(std::filesystem::exists(file.named_temporary()));
      EXPECT_EQ(file.named_temporary().parent_path(), dir.path());
    }
  }
  EXPECT_TRUE(dir.files().empty());
}

TEST(AtomicFile, CommitCreatesTheTarget) {
  TempDir dir;
  io::AtomicFile file(dir / "new.txt");
  file.write("line 1\n");
  file.write("line 2\n");
  EXPECT_TRUE(dir.files().empty()) << "visible before the commit";
  file.commit();
  EXPECT_EQ(test::read_text(dir / "new.txt"), "line 1\nline 2\n");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"new.txt"});
  EXPECT_THROW(file.write("more"), Error);
}

TEST(AtomicFile, CommitWithoutWriteThrows) {
  TempDir dir;
  io::AtomicFile file(dir / "a.txt");
  EXPECT_THROW(file.commit(), Error);
  EXPECT_TRUE(dir.files().empty());
}

TEST(AtomicFile, CommitOntoADirectoryThrowsAndLeavesIt) {
  TempDir dir;
  std::filesystem::create_directory(dir / "d");
  {
    io::AtomicFile file(dir / "d");
    file.write("x");
    EXPECT_THROW(file.commit(), Error);
  }
  EXPECT_EQ(dir.files(), std::vector<std::string>{"d"});
  EXPECT_TRUE(std::filesystem::is_directory(dir / "d"));
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

TEST(StreamedFileWriter, AChildProcessWritesTheTemporary) {
  TempDir dir;
  test::write_file(dir / "plot.png", "old");
  StreamedFileWriter plot(dir / "plot.png");
  const std::string path = plot.path_for_child_process();
  // What gnuplot's `set output PATH` or ffmpeg's output argument would do: open and truncate.
  ASSERT_EQ(std::system(("printf 'new image' > '" + path + "'").c_str()), 0) << path;
  EXPECT_EQ(test::read_text(dir / "plot.png"), "old") << "replaced before the commit";
  plot.commit();
  EXPECT_EQ(test::read_text(dir / "plot.png"), "new image");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"plot.png"});
}

TEST(StreamedFileWriter, AChildProcessOutputIsDroppedWithoutCommit) {
  TempDir dir;
  {
    StreamedFileWriter video(dir / "v.mp4");
    ASSERT_EQ(std::system(("printf 'frames' > '" + video.path_for_child_process() + "'").c_str()),
              0);
  }
  EXPECT_TRUE(dir.files().empty());
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
