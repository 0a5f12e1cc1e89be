// SPDX-License-Identifier: Apache-2.0
#include "seqio/ply_values.h"

#include <cmath>
#include <cstring>
#include <string>
#include <string_view>

#include "seqio/endian.h"
#include "seqio/text_scan.h"

namespace animc {
namespace {

double integerFromBits(PlyType type, uint64_t bits) {
  switch (type) {
    case PlyType::kInt8:
      return double(int8_t(bits));
    case PlyType::kInt16:
      return double(int16_t(bits));
    case PlyType::kInt32:
      return double(int32_t(bits));
    default:
      return double(bits);  // unsigned types
  }
}

bool inIntegerRange(PlyType type, double v) {
  switch (type) {
    case PlyType::kInt8:
      return v >= -128 && v <= 127;
    case PlyType::kUint8:
      return v >= 0 && v <= 255;
    case PlyType::kInt16:
      return v >= -32768 && v <= 32767;
    case PlyType::kUint16:
      return v >= 0 && v <= 65535;
    case PlyType::kInt32:
      return v >= -2147483648.0 && v <= 2147483647.0;
    case PlyType::kUint32:
      return v >= 0 && v <= 4294967295.0;
    default:
      return true;
  }
}

}  // namespace

bool PlyValueReader::read(PlyType type, double* value) {
  return format_ == PlyFormat::kAscii ? readAscii(type, value) : readBinary(type, value);
}

bool PlyValueReader::fail(Status status) {
  status_ = std::move(status);
  return false;
}

bool PlyValueReader::readBinary(PlyType type, double* value) {
  size_t n = plyTypeSize(type);
  if (size_ - pos_ < n) return fail(truncated("data ends early at byte " + std::to_string(pos_)));
  uint64_t bits = 0;
  bool big = format_ == PlyFormat::kBinaryBigEndian;
  for (size_t i = 0; i < n; ++i) {
    size_t shift = 8 * (big ? n - 1 - i : i);
    bits |= uint64_t(data_[pos_ + i]) << shift;
  }
  pos_ += n;
  if (type == PlyType::kFloat32) {
    *value = bitsToFloat(uint32_t(bits));
  } else if (type == PlyType::kFloat64) {
    std::memcpy(value, &bits, 8);
  } else {
    *value = integerFromBits(type, bits);
  }
  return true;
}

bool PlyValueReader::readAscii(PlyType type, double* value) {
  const char* base = reinterpret_cast<const char*>(data_);
  TokenCursor cursor(base + pos_, base + size_);
  std::string_view token;
  if (!cursor.next(&token))
    return fail(truncated("data ends early at byte " + std::to_string(pos_)));
  size_t token_offset = size_t(token.data() - base);
  pos_ = size_t(cursor.position() - base);
  if (!parseDouble(token, value))
    return fail(corrupt("bad number '" + std::string(token.substr(0, 40)) + "' at byte " +
                        std::to_string(token_offset)));
  if (plyTypeIsInteger(type) && (std::floor(*value) != *value || !inIntegerRange(type, *value)))
    return fail(corrupt("'" + std::string(token.substr(0, 40)) + "' at byte " +
                        std::to_string(token_offset) + " is not a valid integer of its type"));
  return true;
}

}  // namespace animc
