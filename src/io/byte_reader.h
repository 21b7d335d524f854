#pragma once
// Reading fixed-size little- or big-endian numbers from an in-memory binary file.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <type_traits>
#include <utility>

namespace deformcd::io {

/// A cursor over bytes. Callers check has() before each read and report truncation themselves,
/// since only they know which element was being read.
class ByteReader {
 public:
  ByteReader(std::string_view data, std::size_t offset, bool big_endian)
      : data_(data), pos_(offset), swap_(big_endian != (std::endian::native == std::endian::big)) {}

  [[nodiscard]] bool has(std::size_t bytes) const { return data_.size() - pos_ >= bytes; }
  [[nodiscard]] std::size_t remaining() const { return data_.size() - pos_; }
  [[nodiscard]] std::size_t offset() const { return pos_; }

  /// Reads an arithmetic value of T's size; has(sizeof(T)) must hold.
  template <class T>
  requires std::is_arithmetic_v<T> T read() {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, data_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    if (swap_) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) {
        std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
      }
    }
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  }

  void skip(std::size_t bytes) { pos_ += bytes; }

 private:
  std::string_view data_;
  std::size_t pos_;
  bool swap_;
};

}  // namespace deformcd::io
