#pragma once
// What the GL failure tests share: the message of the GlError a call throws.

#include <gtest/gtest.h>

#include <string>

#include "deformcd/error.h"

namespace deformcd::test {

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// The what() of the GlError `f` throws; a test failure (and "") when it throws none.
template <class F>
std::string gl_error_of(F&& f) {
  try {
    f();
  } catch (const GlError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a GlError";
  return {};
}

}  // namespace deformcd::test
