// SPDX-License-Identifier: Apache-2.0
// Little-endian serialisation into a growable buffer (the container's only byte order).
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace animc {

class ByteWriter {
 public:
  void u8(uint8_t v) { bytes_.push_back(v); }
  void u16(uint16_t v) { putLe(v, 2); }
  void u32(uint32_t v) { putLe(v, 4); }
  void u64(uint64_t v) { putLe(v, 8); }
  void f32(float v) { uint32_t u; std::memcpy(&u, &v, 4); u32(u); }
  void f64(double v) { uint64_t u; std::memcpy(&u, &v, 8); u64(u); }
  // LEB128: small counts take one byte.
  void varint(uint64_t v) {
    while (v >= 0x80) { bytes_.push_back(uint8_t(v | 0x80)); v >>= 7; }
    bytes_.push_back(uint8_t(v));
  }
  void append(const uint8_t* data, size_t n) { bytes_.insert(bytes_.end(), data, data + n); }
  void append(const std::vector<uint8_t>& v) { append(v.data(), v.size()); }
  void patchU32(size_t at, uint32_t v) { for (int i = 0; i < 4; ++i) bytes_[at + i] = uint8_t(v >> (8 * i)); }

  size_t size() const { return bytes_.size(); }
  const std::vector<uint8_t>& bytes() const { return bytes_; }
  std::vector<uint8_t>& bytes() { return bytes_; }
  void clear() { bytes_.clear(); }

 private:
  void putLe(uint64_t v, int n) { for (int i = 0; i < n; ++i) bytes_.push_back(uint8_t(v >> (8 * i))); }
  std::vector<uint8_t> bytes_;
};

}  // namespace animc
