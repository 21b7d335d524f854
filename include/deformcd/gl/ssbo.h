#pragma once
/// \file ssbo.h
/// Shader storage buffers: an untyped RAII buffer object and a typed array view of it.
/// Plain GL 4.3 entry points (no direct state access); a context must be current for every
/// call, including destruction.

#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

namespace deformcd::gl {

/// An untyped GL buffer object of fixed size, used as a shader storage buffer. Move-only.
class BufferObject {
 public:
  /// Allocates `bytes` of uninitialized storage. Throws GlError when GL runs out of memory.
  explicit BufferObject(std::size_t bytes);
  ~BufferObject();
  BufferObject(BufferObject&& other) noexcept;             ///< leaves `other` empty (name 0)
  BufferObject& operator=(BufferObject&& other) noexcept;  ///< leaves `other` empty (name 0)
  BufferObject(const BufferObject&) = delete;
  BufferObject& operator=(const BufferObject&) = delete;

  /// Copies `bytes` from `data` to the buffer at `offset`. Waits for shader writes first.
  /// Throws GlError when the range does not fit.
  void upload(const void* data, std::size_t bytes, std::size_t offset = 0);
  /// Copies `bytes` at `offset` into `out`, after earlier shader writes have completed.
  /// Throws GlError when the range does not fit.
  void download(void* out, std::size_t bytes, std::size_t offset = 0) const;
  /// Binds the whole buffer to GL_SHADER_STORAGE_BUFFER binding point `index`.
  void bind_storage(std::uint32_t index) const;

  /// The GL buffer name, for applications that use the buffer directly (e.g. to render).
  [[nodiscard]] std::uint32_t name() const noexcept { return name_; }
  [[nodiscard]] std::size_t size_bytes() const noexcept { return bytes_; }  ///< the buffer's size

 private:
  std::uint32_t name_ = 0;
  std::size_t bytes_ = 0;
};

/// A shader storage buffer holding `size()` elements of T, laid out as in
/// deformcd/gpu_layout.h (T must match the GLSL std430 struct). Move-only.
template <class T>
class Ssbo {
  static_assert(std::is_trivially_copyable_v<T>, "Ssbo elements are copied byte for byte");

 public:
  /// `count` uninitialized elements.
  explicit Ssbo(std::size_t count) : buffer_(count * sizeof(T)), count_(count) {}
  /// As many elements as `data`, initialized from it.
  explicit Ssbo(std::span<const T> data) : Ssbo(data.size()) { upload(data); }
  /// Leaves `other` empty.
  Ssbo(Ssbo&& other) noexcept
      : buffer_(std::move(other.buffer_)), count_(std::exchange(other.count_, 0)) {}
  /// Leaves `other` empty.
  Ssbo& operator=(Ssbo&& other) noexcept {
    buffer_ = std::move(other.buffer_);
    count_ = std::exchange(other.count_, 0);
    return *this;
  }

  /// Overwrites elements [first, first + data.size()). Throws GlError when they do not fit.
  void upload(std::span<const T> data, std::size_t first = 0) {
    buffer_.upload(data.data(), data.size_bytes(), first * sizeof(T));
  }
  /// All elements.
  [[nodiscard]] std::vector<T> download() const { return download(0, count_); }
  /// Elements [first, first + count). Throws GlError when they do not fit.
  [[nodiscard]] std::vector<T> download(std::size_t first, std::size_t count) const {
    std::vector<T> out(count);
    buffer_.download(out.data(), count * sizeof(T), first * sizeof(T));
    return out;
  }
  /// Binds the buffer to GL_SHADER_STORAGE_BUFFER binding point `index`
  /// (a deformcd::gpu::Binding for the simulation's buffers).
  void bind(std::uint32_t index) const { buffer_.bind_storage(index); }

  /// The GL buffer name, for applications that use the buffer directly (e.g. to render).
  [[nodiscard]] std::uint32_t name() const noexcept { return buffer_.name(); }
  [[nodiscard]] std::size_t size() const noexcept { return count_; }  ///< number of elements

 private:
  BufferObject buffer_;
  std::size_t count_ = 0;
};

}  // namespace deformcd::gl
