#pragma once
// Helpers for the io tests: a scratch directory (support/temp_dir.h), file writers, and a check
// for InputErrors.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <string>
#include <string_view>

#include "deformcd/error.h"
#include "support/temp_dir.h"

namespace deformcd::test {

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
