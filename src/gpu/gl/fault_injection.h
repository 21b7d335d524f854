#pragma once
// Test-only fault injection: makes the GL backend fail where a driver can, so that tests prove
// each failure is a clear GlError that leaves the last good state intact (issue 16, point 3).
// Compiled in always and inert unless a test arms it: a hooked operation costs one atomic
// increment (the count below). Not part of the public API: only src/gpu/gl and tests include
// this header.
//
//   gl::fault::ScopedFault oom(gl::fault::Kind::kBufferAllocation, 3);  // the 3rd from now fails
//
// The state is process-wide, on purpose: the hooked operations (a BufferObject's constructor,
// a shader compile, a context's make_current) sit under objects a test cannot reach, and one
// counter per kind is all a test needs to aim at "the Nth allocation of this upload". A test
// that arms a fault disarms it when done (ScopedFault does); nothing else may arm one.

#include <cstdint>
#include <limits>

namespace deformcd::gl::fault {

enum class Kind {
  // BufferObject's glBufferData is skipped and reported as GL_OUT_OF_MEMORY, the driver's error
  // for an allocation it refuses.
  kBufferAllocation,
  // compile_shader_stage hands the driver the source with a line appended that uses an
  // undeclared name, so that the real driver fails the compile with its own log, as another
  // driver might.
  kShaderCompile,
  // EglHeadlessContext::make_current reports EGL_BAD_ACCESS without calling eglMakeCurrent
  // (the context is current in another thread), leaving the current context as it was.
  kMakeCurrent,
};

inline constexpr std::uint64_t kForever = std::numeric_limits<std::uint64_t>::max();

// Operations of `kind` `first` (1: the next one) to `first + count - 1` from now fail.
void arm(Kind kind, std::uint64_t first = 1, std::uint64_t count = 1);
void disarm(Kind kind);
// Operations of `kind` this process has made, failed ones included: run a step once and read
// the difference to learn how many allocations (compiles...) it makes, then aim at each.
[[nodiscard]] std::uint64_t operations(Kind kind);
// For the hooked operations: counts one; true when it must fail.
[[nodiscard]] bool should_fail(Kind kind);

// Arms a fault for one scope.
class ScopedFault {
 public:
  explicit ScopedFault(Kind kind, std::uint64_t first = 1, std::uint64_t count = 1) : kind_(kind) {
    arm(kind, first, count);
  }
  ~ScopedFault() { disarm(kind_); }
  ScopedFault(const ScopedFault&) = delete;
  ScopedFault& operator=(const ScopedFault&) = delete;

 private:
  Kind kind_;
};

}  // namespace deformcd::gl::fault
