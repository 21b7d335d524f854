#include "gpu/gl/position_layout.h"

#include <algorithm>
#include <limits>
#include <string>

#include "deformcd/error.h"

namespace deformcd::gl {

namespace {

using Kind = collision::PositionSource::Kind;
using std::to_string;

constexpr std::uint64_t kWordsMax = std::numeric_limits<std::uint32_t>::max();

std::string label(std::span<const std::string> labels, std::size_t m) {
  return m < labels.size() ? labels[m] : "mesh " + to_string(m);
}

bool all_in_one_gl_buffer(std::span<const collision::PositionSource> sources) {
  for (const collision::PositionSource& s : sources) {
    if (s.kind != Kind::kGl || s.gl_buffer != sources.front().gl_buffer) return false;
  }
  return !sources.empty();
}

}  // namespace

std::uint64_t checked_position_span(const collision::PositionSource& s, std::uint32_t vertex_count,
                                    const std::string& name) {
  const auto fail = [&](const std::string& what) {
    throw Error("GL collision: " + name + "'s positions: " + what);
  };
  if (s.kind == Kind::kNone) fail("none set");
  if (s.kind == Kind::kHost && s.host == nullptr) fail("a null host array");
  if (s.kind == Kind::kGl && s.gl_buffer == 0) fail("GL buffer 0 (no buffer)");
  if (s.stride_bytes % 4 != 0 || s.stride_bytes < 12) {
    fail("a stride of " + to_string(s.stride_bytes) +
         " bytes, not a multiple of 4 of at least 12 (x, y, z floats)");
  }
  if (s.kind == Kind::kGl && s.offset_bytes % 4 != 0) {
    fail("an offset of " + to_string(s.offset_bytes) + " bytes, not a multiple of 4");
  }
  // The shaders' uint arithmetic: every word of the mesh, offset included, below 2^32 (checked
  // on words, before any product can overflow 64 bits).
  const std::uint64_t stride_words = s.stride_bytes / 4;
  const std::uint64_t gaps = vertex_count == 0 ? 0 : vertex_count - 1;
  const std::uint64_t offset_words = s.kind == Kind::kGl ? s.offset_bytes / 4 : 0;
  const bool fits = stride_words <= (kWordsMax - 2) / std::max<std::uint64_t>(gaps, 1) &&
                    offset_words <= kWordsMax - 2 - stride_words * gaps;
  if (!fits) {
    fail("vertices reaching past float 2^32 - 1 of the buffer (offset " +
         to_string(s.offset_bytes) + ", stride " + to_string(s.stride_bytes) + " bytes, " +
         to_string(vertex_count) + " vertices), beyond the shaders' uint indices");
  }
  return position_span_bytes(s.stride_bytes, vertex_count);
}

std::uint64_t position_span_bytes(std::uint64_t stride_bytes, std::uint32_t vertex_count) {
  return vertex_count == 0 ? 0 : stride_bytes * (vertex_count - 1) + 3 * sizeof(float);
}

PositionLayout plan_position_layout(std::span<const collision::PositionSource> sources,
                                    std::span<const std::uint32_t> vertex_counts,
                                    std::span<const std::string> labels) {
  if (sources.size() != vertex_counts.size()) {
    throw Error("GL collision: " + to_string(sources.size()) + " position sources for " +
                to_string(vertex_counts.size()) + " meshes");
  }
  PositionLayout layout;
  layout.shared_buffer = all_in_one_gl_buffer(sources) ? sources.front().gl_buffer : 0;
  for (std::size_t m = 0; m < sources.size(); ++m) {
    const collision::PositionSource& s = sources[m];
    MeshPositionLayout mesh;
    mesh.span_bytes = checked_position_span(s, vertex_counts[m], label(labels, m));
    mesh.word_stride = static_cast<std::uint32_t>(s.stride_bytes / 4);
    if (layout.in_place()) {
      mesh.word_offset = static_cast<std::uint32_t>(s.offset_bytes / 4);
    } else {
      // Spans are multiples of 4 bytes: every region starts on a float.
      mesh.region_offset = layout.gathered_bytes;
      layout.gathered_bytes += mesh.span_bytes;
      if (layout.gathered_bytes / 4 > kWordsMax + 1) {
        throw Error("GL collision: the positions of the meshes up to " + label(labels, m) +
                    " take " + to_string(layout.gathered_bytes) +
                    " bytes, more than the shaders' uint indices reach (2^32 floats)");
      }
      mesh.word_offset = static_cast<std::uint32_t>(mesh.region_offset / 4);
    }
    layout.meshes.push_back(mesh);
  }
  return layout;
}

}  // namespace deformcd::gl
