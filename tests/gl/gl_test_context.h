#pragma once
// A GL context for tests, or a clean skip when the machine cannot give one.
//
//   class MyTest : public deformcd::gl::test_support::GlTest {};
//   TEST_F(MyTest, Works) { /* a 4.3 context is current here */ }
//
// GL tests skip, with the reason, when no context can be created. Set DEFORMCD_REQUIRE_GL=1
// (e.g. in CI on a machine that has Mesa) to make that a failure instead.

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "deformcd/error.h"
#include "deformcd/gl/context.h"

namespace deformcd::gl::test_support {

inline bool gl_required() {
  const char* value = std::getenv("DEFORMCD_REQUIRE_GL");
  return value != nullptr && *value != '\0' && std::string_view(value) != "0";
}

/// Skips the current test, or fails it under DEFORMCD_REQUIRE_GL, because GL is unavailable.
#define DEFORMCD_GL_UNAVAILABLE(why)                          \
  do {                                                        \
    if (::deformcd::gl::test_support::gl_required()) {        \
      FAIL() << "DEFORMCD_REQUIRE_GL is set, but: " << (why); \
    } else {                                                  \
      GTEST_SKIP() << "no OpenGL 4.3 context: " << (why);     \
    }                                                         \
  } while (0)

struct ContextAttempt {
  std::unique_ptr<Context> context;  ///< null when creation failed
  std::string why_not;               ///< the GlError message then
};

inline ContextAttempt try_create_context(const ContextOptions& options = {}) {
  try {
    return {create_headless_context(options), {}};
  } catch (const GlError& e) {
    return {nullptr, e.what()};
  }
}

/// One context per test process, created on first use with the default options.
inline ContextAttempt& shared_context() {
  static ContextAttempt attempt = try_create_context();
  return attempt;
}

/// Fixture: the shared context is current in every test, or the test is skipped.
class GlTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ContextAttempt& shared = shared_context();
    if (!shared.context) DEFORMCD_GL_UNAVAILABLE(shared.why_not);
    // Another test may have made its own context current since.
    shared.context->make_current();
  }

  [[nodiscard]] Context& context() { return *shared_context().context; }
};

/// Sets (or, with nullopt, unsets) an environment variable for one scope.
class ScopedEnv {
 public:
  ScopedEnv(std::string name, std::optional<std::string> value) : name_(std::move(name)) {
    if (const char* old = std::getenv(name_.c_str())) old_ = old;
    apply(value);
  }
  ~ScopedEnv() { apply(old_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  void apply(const std::optional<std::string>& value) {
    if (value) {
      ::setenv(name_.c_str(), value->c_str(), 1);
    } else {
      ::unsetenv(name_.c_str());
    }
  }

  std::string name_;
  std::optional<std::string> old_;
};

}  // namespace deformcd::gl::test_support
