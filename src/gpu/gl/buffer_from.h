#pragma once
// An SSBO holding a copy of a host array, for the backends' upload().

#include <algorithm>
#include <span>
#include <vector>

#include "deformcd/gl/ssbo.h"

namespace deformcd::gl {

/// A buffer of at least one element: binding a zero-size buffer is an error on some drivers,
/// and an empty world still dispatches nothing that would read the placeholder.
template <class T>
Ssbo<T> make_buffer(const std::vector<T>& data) {
  Ssbo<T> buffer(std::max<std::size_t>(data.size(), 1));
  buffer.upload(std::span<const T>(data));
  return buffer;
}

}  // namespace deformcd::gl
