#pragma once
// Building binary STL and PLY files in tests, byte by byte, in either endianness.

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>
#include <string_view>

namespace deformcd::test {

class ByteWriter {
 public:
  explicit ByteWriter(bool big_endian = false) : big_endian_(big_endian) {}

  template <class T>
  ByteWriter& put(T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if (big_endian_ != (std::endian::native == std::endian::big)) {
      std::reverse(bytes, bytes + sizeof(T));
    }
    data_.append(bytes, sizeof(T));
    return *this;
  }
  ByteWriter& text(std::string_view s) {
    data_ += s;
    return *this;
  }

  [[nodiscard]] const std::string& data() const { return data_; }

 private:
  bool big_endian_;
  std::string data_;
};

}  // namespace deformcd::test
