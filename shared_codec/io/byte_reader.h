// SPDX-License-Identifier: Apache-2.0
// Bounds-checked little-endian reads over untrusted bytes. A failed read does not move the
// cursor and names the field and its offset; nothing here can read past the span.
#pragma once
#include <cstdint>
#include <cstring>
#include <string>

#include "core/status.h"

namespace animc {

class ByteReader {
 public:
  ByteReader() = default;
  // base_offset: where data sits in the file, so messages give absolute offsets.
  ByteReader(const uint8_t* data, size_t size, uint64_t base_offset = 0)
      : data_(data), size_(size), base_(base_offset) {}

  size_t remaining() const { return size_ - pos_; }
  size_t position() const { return pos_; }
  uint64_t offset() const { return base_ + pos_; }
  const uint8_t* cursor() const { return data_ + pos_; }

  Result<uint8_t> u8(const char* field) { return readLe<uint8_t>(field, 1); }
  Result<uint16_t> u16(const char* field) { return readLe<uint16_t>(field, 2); }
  Result<uint32_t> u32(const char* field) { return readLe<uint32_t>(field, 4); }
  Result<uint64_t> u64(const char* field) { return readLe<uint64_t>(field, 8); }
  Result<float> f32(const char* field);
  Result<double> f64(const char* field);
  Result<uint64_t> varint(const char* field);
  Status skip(size_t n, const char* field);
  // A reader over the next n bytes; this reader moves past them.
  Result<ByteReader> subReader(size_t n, const char* field);

  Status truncatedAt(const char* field) const;

 private:
  template <class T>
  Result<T> readLe(const char* field, size_t n) {
    if (remaining() < n) return truncatedAt(field);
    uint64_t v = 0;
    for (size_t i = 0; i < n; ++i) v |= uint64_t(data_[pos_ + i]) << (8 * i);
    pos_ += n;
    return T(v);
  }

  const uint8_t* data_ = nullptr;
  size_t size_ = 0;
  size_t pos_ = 0;
  uint64_t base_ = 0;
};

}  // namespace animc
