// SPDX-License-Identifier: Apache-2.0
#include "io/byte_reader.h"

namespace animc {

Status ByteReader::truncatedAt(const char* field) const {
  return truncated(std::string(field) + " at byte " + std::to_string(offset()) +
                   ": data ends early");
}

Result<float> ByteReader::f32(const char* field) {
  ANIMC_ASSIGN_OR_RETURN(uint32_t u, u32(field));
  float v;
  std::memcpy(&v, &u, 4);
  return v;
}

Result<double> ByteReader::f64(const char* field) {
  ANIMC_ASSIGN_OR_RETURN(uint64_t u, u64(field));
  double v;
  std::memcpy(&v, &u, 8);
  return v;
}

Result<uint64_t> ByteReader::varint(const char* field) {
  uint64_t v = 0;
  for (size_t i = 0; i < 10; ++i) {
    if (pos_ + i >= size_) return truncatedAt(field);
    uint8_t b = data_[pos_ + i];
    v |= uint64_t(b & 0x7f) << (7 * i);
    if (!(b & 0x80)) {
      pos_ += i + 1;
      return v;
    }
  }
  return corrupt(std::string(field) + " at byte " + std::to_string(offset()) +
                 ": varint longer than 10 bytes");
}

Status ByteReader::skip(size_t n, const char* field) {
  if (remaining() < n) return truncatedAt(field);
  pos_ += n;
  return Status();
}

Result<ByteReader> ByteReader::subReader(size_t n, const char* field) {
  if (remaining() < n) return truncatedAt(field);
  ByteReader sub(data_ + pos_, n, offset());
  pos_ += n;
  return sub;
}

}  // namespace animc
