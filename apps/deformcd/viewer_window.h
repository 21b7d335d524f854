#pragma once
// The `deformcd view` window: GLFW, an OpenGL 4.3 core context, and the user's input gathered
// between frames.

#include <string>

struct GLFWwindow;

namespace deformcd::app {

// What the user did since the last poll. Mouse motion is in window pixels.
struct ViewerInput {
  double orbit_x = 0.0, orbit_y = 0.0;  // drag with the left button
  double pan_x = 0.0, pan_y = 0.0;      // drag with the right or middle button
  double scroll = 0.0;                  // wheel steps, positive away from the user
  bool toggle_pause = false;            // space
  bool step_once = false;               // N or right arrow
  bool cycle_broadphase = false;        // B
  bool toggle_mode = false;             // W
  bool reset_camera = false;            // R
  bool quit = false;                    // Esc, Q, or the window closed
};

class ViewerWindow {
 public:
  // Opens a window with a current 4.3 core context (4x multisampled). Throws Error when there
  // is no display (no DISPLAY or WAYLAND_DISPLAY, or GLFW cannot reach it), or when no 4.3
  // context can be had; both messages point to `deformcd render`, which needs no display.
  ViewerWindow(int width, int height, const std::string& title);
  ~ViewerWindow();
  ViewerWindow(const ViewerWindow&) = delete;
  ViewerWindow& operator=(const ViewerWindow&) = delete;

  // Processes pending events (waiting up to `wait_seconds` for one when positive) and returns
  // the input gathered since the last call.
  ViewerInput poll(double wait_seconds = 0.0);
  void swap_buffers();
  void set_title(const std::string& title);
  void make_current();
  void framebuffer_size(int& width, int& height) const;
  // In the units of mouse motion (differs from the framebuffer's on high-DPI screens).
  [[nodiscard]] int window_height() const;

 private:
  static void on_key(GLFWwindow* window, int key, int scancode, int action, int mods);
  static void on_cursor(GLFWwindow* window, double x, double y);
  static void on_scroll(GLFWwindow* window, double dx, double dy);

  GLFWwindow* window_ = nullptr;
  ViewerInput input_;
  double cursor_x_ = 0.0, cursor_y_ = 0.0;
  bool cursor_known_ = false;
};

}  // namespace deformcd::app
