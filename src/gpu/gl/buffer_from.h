#pragma once
// The backends' buffers, allocated so that a failure names the buffer: an SSBO of a given
// count, or holding a copy of a host array (upload()); and a buffer bound by its name alone.

#include <algorithm>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "deformcd/error.h"
#include "deformcd/gl/ssbo.h"
#include "gpu/gl/simulation_upload_checks.h"

namespace deformcd::gl {

// Whose buffer it is and which ("GL collision", "Face Pair", 10), for the GlError of a failed
// allocation.
struct BufferLabel {
  std::string_view owner;
  std::string_view name;
  std::uint32_t binding = 0;
};

// The label of the buffer at `binding` in `sizes` (an upload's list; the binding must be there).
inline BufferLabel label_of(std::span<const BufferSize> sizes, std::uint32_t binding,
                            std::string_view owner) {
  const auto it = std::find_if(sizes.begin(), sizes.end(),
                               [binding](const BufferSize& b) { return b.binding == binding; });
  return {owner, it != sizes.end() ? it->name : std::string_view("a buffer"), binding};
}

// Binds GL buffer `buffer` (a name, whoever owns it) whole at shader storage binding `binding`.
void bind_storage_buffer(std::uint32_t binding, std::uint32_t buffer);

// "<owner>: allocating <name> (SSBO <binding>), <bytes> bytes (<count> x <element>), failed:
// <cause>", the cause being BufferObject's GlError (the driver's error, e.g. GL_OUT_OF_MEMORY).
GlError allocation_error(const BufferLabel& label, std::uint64_t count, std::uint64_t element_bytes,
                         const GlError& cause);

// `count` uninitialized elements; GlError naming `label` when the driver refuses them.
template <class T>
Ssbo<T> allocate(std::size_t count, const BufferLabel& label) {
  try {
    return Ssbo<T>(count);
  } catch (const GlError& e) {
    throw allocation_error(label, count, sizeof(T), e);
  }
}

/// A buffer of at least one element: binding a zero-size buffer is an error on some drivers,
/// and an empty world still dispatches nothing that would read the placeholder.
template <class T>
Ssbo<T> make_buffer(const std::vector<T>& data, const BufferLabel& label) {
  Ssbo<T> buffer = allocate<T>(std::max<std::size_t>(data.size(), 1), label);
  buffer.upload(std::span<const T>(data));
  return buffer;
}

}  // namespace deformcd::gl
