#include "deformcd/gl/timer_query.h"

#include <epoxy/gl.h>

#include <utility>

#include "gpu/gl/gl_check.h"

namespace deformcd::gl {

TimerQuery::TimerQuery() {
  GLuint name = 0;
  DEFORMCD_GL_CHECK(glGenQueries(1, &name));
  name_ = name;
}

TimerQuery::~TimerQuery() {
  if (name_ != 0) glDeleteQueries(1, &name_);
}

TimerQuery::TimerQuery(TimerQuery&& other) noexcept : name_(std::exchange(other.name_, 0)) {}

TimerQuery& TimerQuery::operator=(TimerQuery&& other) noexcept {
  if (this != &other) {
    if (name_ != 0) glDeleteQueries(1, &name_);
    name_ = std::exchange(other.name_, 0);
  }
  return *this;
}

void TimerQuery::begin() {
  DEFORMCD_GL_CHECK(glBeginQuery(GL_TIME_ELAPSED, name_));
}

void TimerQuery::end() {
  DEFORMCD_GL_CHECK(glEndQuery(GL_TIME_ELAPSED));
}

bool TimerQuery::ready() const {
  GLuint available = GL_FALSE;
  DEFORMCD_GL_CHECK(glGetQueryObjectuiv(name_, GL_QUERY_RESULT_AVAILABLE, &available));
  return available != GL_FALSE;
}

std::uint64_t TimerQuery::elapsed_ns() const {
  GLuint64 ns = 0;
  DEFORMCD_GL_CHECK(glGetQueryObjectui64v(name_, GL_QUERY_RESULT, &ns));
  return ns;
}

}  // namespace deformcd::gl
