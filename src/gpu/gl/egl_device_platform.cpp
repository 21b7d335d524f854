// The EGL device platform: enumerate devices, open each as a display, take the first one that
// gives a 4.3 core context.

#include <epoxy/egl.h>

#include <algorithm>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "deformcd/error.h"
#include "gpu/gl/egl_display.h"
#include "gpu/gl/egl_headless_context.h"
#include "gpu/gl/egl_platforms.h"

// From EGL_EXT_device_drm_render_node, newer than libepoxy 1.5's registry.
#ifndef EGL_DRM_RENDER_NODE_FILE_EXT
#define EGL_DRM_RENDER_NODE_FILE_EXT 0x3377
#endif

namespace deformcd::gl::detail {

namespace {

bool is_software(EGLDeviceEXT device) {
  return extension_listed(eglQueryDeviceStringEXT(device, EGL_EXTENSIONS),
                          "EGL_MESA_device_software");
}

// "device 1 of 2 (/dev/dri/renderD128)" or "device 0 of 1 (software)".
std::string describe_device(EGLDeviceEXT device, std::size_t index, std::size_t count) {
  std::string text = "device " + std::to_string(index) + " of " + std::to_string(count);
  const char* extensions = eglQueryDeviceStringEXT(device, EGL_EXTENSIONS);
  const char* node = nullptr;
  if (extension_listed(extensions, "EGL_EXT_device_drm_render_node")) {
    node = eglQueryDeviceStringEXT(device, EGL_DRM_RENDER_NODE_FILE_EXT);
  }
  if (node == nullptr && extension_listed(extensions, "EGL_EXT_device_drm")) {
    node = eglQueryDeviceStringEXT(device, EGL_DRM_DEVICE_FILE_EXT);
  }
  if (is_software(device)) {
    text += " (software)";
  } else if (node != nullptr) {
    text += std::string(" (") + node + ")";
  }
  return text;
}

std::vector<EGLDeviceEXT> query_devices() {
  EGLint count = 0;
  if (eglQueryDevicesEXT(0, nullptr, &count) != EGL_TRUE) {
    throw GlError("eglQueryDevicesEXT failed: " + egl_error_name(eglGetError()));
  }
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  if (count > 0 && eglQueryDevicesEXT(count, devices.data(), &count) != EGL_TRUE) {
    throw GlError("eglQueryDevicesEXT failed: " + egl_error_name(eglGetError()));
  }
  devices.resize(static_cast<std::size_t>(count));
  return devices;
}

}  // namespace

std::unique_ptr<Context> create_device_platform_context(DeviceSelection selection, bool debug) {
  for (const char* extension : {"EGL_EXT_device_enumeration", "EGL_EXT_platform_device"}) {
    if (!has_egl_client_extension(extension)) {
      throw GlError(std::string("EGL client extension ") + extension + " is missing");
    }
  }
  const std::vector<EGLDeviceEXT> devices = query_devices();
  if (devices.empty()) throw GlError("no EGL devices");

  // Hardware devices first, in enumeration order.
  std::vector<std::size_t> order(devices.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_partition(order.begin(), order.end(),
                        [&](std::size_t i) { return !is_software(devices[i]); });

  std::string reasons;
  for (const std::size_t i : order) {
    const std::string name = describe_device(devices[i], i, devices.size());
    const bool software = is_software(devices[i]);
    if ((selection == DeviceSelection::kHardwareOnly && software) ||
        (selection == DeviceSelection::kSoftwareOnly && !software)) {
      reasons +=
          "; " + name + ": " +
          (software ? "software, tried after the surfaceless platform" : "hardware, already tried");
      continue;
    }
    std::optional<EglDisplay> display;
    try {
      display.emplace(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr));
    } catch (const GlError& e) {
      reasons += "; " + name + ": " + e.what();
      continue;
    }
    try {
      return std::make_unique<EglHeadlessContext>(std::move(*display), "egl-device", name, debug);
    } catch (const GlError& e) {
      reasons += std::string("; ") + e.what();  // already names the device
    }
  }
  throw GlError(reasons.substr(2));
}

}  // namespace deformcd::gl::detail
