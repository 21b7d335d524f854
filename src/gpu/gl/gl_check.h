#pragma once
// DEFORMCD_GL_CHECK(call): in debug builds (NDEBUG undefined), runs `call`, then throws GlError
// naming the call, file and line when glGetError reports an error, with any KHR_debug error
// messages the context collected. In release builds it is exactly `call`: no overhead.
// Works for calls with and without a value:
//   DEFORMCD_GL_CHECK(glUseProgram(program));
//   const GLuint shader = DEFORMCD_GL_CHECK(glCreateShader(GL_COMPUTE_SHADER));

#include <string>
#include <type_traits>

namespace deformcd::gl::detail {

// "GL_INVALID_ENUM"... for a glGetError code.
std::string gl_error_name(unsigned error);

// Throws GlError when glGetError reports errors (draining all of them).
void throw_if_gl_error(const char* call, const char* file, int line);

template <class Call>
decltype(auto) checked_gl_call(Call&& call, const char* text, const char* file, int line) {
  if constexpr (std::is_void_v<decltype(call())>) {
    call();
    throw_if_gl_error(text, file, line);
  } else {
    decltype(auto) result = call();
    throw_if_gl_error(text, file, line);
    return result;
  }
}

}  // namespace deformcd::gl::detail

#ifdef NDEBUG
#define DEFORMCD_GL_CHECK(...) (__VA_ARGS__)
#else
#define DEFORMCD_GL_CHECK(...)                                                             \
  ::deformcd::gl::detail::checked_gl_call([&]() -> decltype(auto) { return __VA_ARGS__; }, \
                                          #__VA_ARGS__, __FILE__, __LINE__)
#endif
