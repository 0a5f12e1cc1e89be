// SPDX-License-Identifier: Apache-2.0
// The PLY header: format line, elements with their scalar and list properties.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"

namespace animc {

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };
enum class PlyType : uint8_t {
  kInt8,
  kUint8,
  kInt16,
  kUint16,
  kInt32,
  kUint32,
  kFloat32,
  kFloat64
};

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;  // for a list: the type of its items
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  size_t data_offset = 0;  // first byte after the "end_header" line
};

size_t plyTypeSize(PlyType type);
bool plyTypeIsInteger(PlyType type);

// Messages name the header line but not the file (callers add it).
Result<PlyHeader> parsePlyHeader(const uint8_t* data, size_t size);

// Smallest encoding of one instance of `element`: lists may be empty, ASCII values need a
// character and a separator each.
uint64_t plyMinInstanceBytes(const PlyElement& element, bool ascii);

// Rejects headers announcing more elements than `data_size` bytes can hold, before anything
// is allocated for them.
Status checkPlyDataSize(const PlyHeader& header, size_t data_size);

}  // namespace animc
