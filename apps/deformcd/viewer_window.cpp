#include "viewer_window.h"

#define GLFW_INCLUDE_NONE  // GL comes from epoxy, through deformcd's libraries
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <string>

#include "deformcd/error.h"

namespace deformcd::app {

namespace {

// GLFW reports errors through a callback; the last one goes into our error messages.
std::string& last_glfw_error() {
  static std::string error;
  return error;
}

void remember_glfw_error(int code, const char* description) {
  last_glfw_error() = std::string(description) + " (GLFW error 0x" + std::to_string(code) + ")";
}

bool has_display() {
  for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY"}) {
    const char* value = std::getenv(name);
    if (value != nullptr && *value != '\0') return true;
  }
  return false;
}

constexpr const char* kUseRender =
    "; deformcd render SCENE --frames ... --out DIR draws images without a display";

}  // namespace

ViewerWindow::ViewerWindow(int width, int height, const std::string& title) {
  if (!has_display()) {
    throw Error(std::string("deformcd view needs a display, and neither DISPLAY nor "
                            "WAYLAND_DISPLAY is set (run it under xvfb-run for a virtual one)") +
                kUseRender);
  }
  glfwSetErrorCallback(remember_glfw_error);
  if (glfwInit() != GLFW_TRUE) {
    throw Error("deformcd view cannot open a window on the display: " + last_glfw_error() +
                kUseRender);
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, 4);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (window_ == nullptr) {
    const std::string why = last_glfw_error();
    glfwTerminate();
    throw GlError("deformcd view cannot create a window with an OpenGL 4.3 core context: " + why +
                  kUseRender);
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(1);
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, on_key);
  glfwSetCursorPosCallback(window_, on_cursor);
  glfwSetScrollCallback(window_, on_scroll);
}

ViewerWindow::~ViewerWindow() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

ViewerInput ViewerWindow::poll(double wait_seconds) {
  if (wait_seconds > 0.0) {
    glfwWaitEventsTimeout(wait_seconds);
  } else {
    glfwPollEvents();
  }
  if (glfwWindowShouldClose(window_)) input_.quit = true;
  ViewerInput gathered = input_;
  input_ = ViewerInput{};
  return gathered;
}

void ViewerWindow::swap_buffers() {
  glfwSwapBuffers(window_);
}

void ViewerWindow::set_title(const std::string& title) {
  glfwSetWindowTitle(window_, title.c_str());
}

void ViewerWindow::make_current() {
  glfwMakeContextCurrent(window_);
}

void ViewerWindow::framebuffer_size(int& width, int& height) const {
  glfwGetFramebufferSize(window_, &width, &height);
}

int ViewerWindow::window_height() const {
  int width = 0, height = 0;
  glfwGetWindowSize(window_, &width, &height);
  return height;
}

void ViewerWindow::on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  ViewerInput& in = static_cast<ViewerWindow*>(glfwGetWindowUserPointer(window))->input_;
  switch (key) {
    case GLFW_KEY_SPACE:
      if (action == GLFW_PRESS) in.toggle_pause = true;
      break;
    case GLFW_KEY_N:
    case GLFW_KEY_RIGHT:
      in.step_once = true;  // held down, it keeps stepping
      break;
    case GLFW_KEY_B:
      if (action == GLFW_PRESS) in.cycle_broadphase = true;
      break;
    case GLFW_KEY_W:
      if (action == GLFW_PRESS) in.toggle_mode = true;
      break;
    case GLFW_KEY_R:
      if (action == GLFW_PRESS) in.reset_camera = true;
      break;
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q:
      in.quit = true;
      break;
    default:
      break;
  }
}

void ViewerWindow::on_cursor(GLFWwindow* window, double x, double y) {
  auto* self = static_cast<ViewerWindow*>(glfwGetWindowUserPointer(window));
  const double dx = self->cursor_known_ ? x - self->cursor_x_ : 0.0;
  const double dy = self->cursor_known_ ? y - self->cursor_y_ : 0.0;
  self->cursor_x_ = x;
  self->cursor_y_ = y;
  self->cursor_known_ = true;
  if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) {
    self->input_.orbit_x += dx;
    self->input_.orbit_y += dy;
  } else if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
             glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS) {
    self->input_.pan_x += dx;
    self->input_.pan_y += dy;
  }
}

void ViewerWindow::on_scroll(GLFWwindow* window, double /*dx*/, double dy) {
  static_cast<ViewerWindow*>(glfwGetWindowUserPointer(window))->input_.scroll += dy;
}

}  // namespace deformcd::app
