// gl_context_probe: creates a headless context in a fresh process, so that tests can change
// the driver's environment (e.g. MESA_GL_VERSION_OVERRIDE, read once per process) first.
// Prints "platform=NAME version=GL_VERSION" and exits 0, or prints the GlError and exits 1.

#include <epoxy/gl.h>

#include <iostream>

#include "deformcd/error.h"
#include "deformcd/gl/context.h"

int main() {
  try {
    const auto context = deformcd::gl::create_headless_context();
    std::cout << "platform=" << context->platform_name()
              << " version=" << reinterpret_cast<const char*>(glGetString(GL_VERSION)) << '\n';
    return 0;
  } catch (const deformcd::GlError& e) {
    std::cout << e.what() << '\n';
    return 1;
  }
}
