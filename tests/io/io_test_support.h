#pragma once
// Helpers for the io tests: a scratch directory, file writers, and a check for InputErrors.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "deformcd/error.h"

namespace deformcd::test {

/// A fresh directory under the system's temporary directory, removed with its contents.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("deformcd_io_" + std::string(info ? info->name() : "test") + "_" +
             std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::filesystem::path operator/(const std::string& name) const {
    return path_ / name;
  }

  /// The names of the files in the directory, hidden ones included, sorted.
  [[nodiscard]] std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(path_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  std::filesystem::path path_;
};

inline std::filesystem::path write_file(const std::filesystem::path& file,
                                        std::string_view contents) {
  std::ofstream out(file, std::ios::binary);
  out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
  EXPECT_TRUE(out.good()) << "cannot write " << file;
  return file;
}

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::filesystem::path data_file(const std::string& name) {
  return std::filesystem::path(DEFORMCD_TEST_DATA_DIR) / "io" / name;
}

/// Runs `read` and checks that it throws an InputError whose message names `file_name`, has
/// line `line` (0: none) and contains every keyword. Returns the message.
template <class Read>
std::string expect_input_error(Read&& read, const std::string& file_name, std::size_t line,
                               std::initializer_list<std::string_view> keywords) {
  try {
    read();
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file_name), std::string::npos) << "no file name in: " << what;
    EXPECT_EQ(e.line(), line) << what;
    if (line > 0) {
      EXPECT_NE(what.find(file_name + ":" + std::to_string(line) + ": "), std::string::npos)
          << "no 'file:line: ' in: " << what;
    }
    for (const std::string_view keyword : keywords) {
      EXPECT_NE(what.find(keyword), std::string::npos) << "no '" << keyword << "' in: " << what;
    }
    return what;
  }
  ADD_FAILURE() << "no InputError thrown (expected one about " << file_name << ")";
  return {};
}

}  // namespace deformcd::test
