// SPDX-License-Identifier: Apache-2.0
// Reads the typed scalars of a PLY body one at a time, in whichever encoding the header
// declared, with bounds checks; a failed read leaves the reason in status().
#pragma once
#include <cstddef>
#include <cstdint>

#include "core/status.h"
#include "seqio/ply_header.h"

namespace animc {

class PlyValueReader {
 public:
  PlyValueReader(PlyFormat format, const uint8_t* data, size_t size, size_t offset)
      : format_(format), data_(data), size_(size), pos_(offset) {}

  // Integer types come back exactly (every PLY integer fits a double).
  bool read(PlyType type, double* value);
  const Status& status() const { return status_; }
  PlyFormat format() const { return format_; }
  // Bytes not read yet.
  size_t remaining() const { return size_ - pos_; }

 private:
  bool readBinary(PlyType type, double* value);
  bool readAscii(PlyType type, double* value);
  bool fail(Status status);

  PlyFormat format_;
  const uint8_t* data_;
  size_t size_;
  size_t pos_;
  Status status_;
};

}  // namespace animc
