// SPDX-License-Identifier: Apache-2.0
// Random-access bytes a reader takes apart: a file, or memory the caller owns. Readers check
// every offset against size() before reading, so a source need not trust them either.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "core/status.h"

namespace animc {

class ByteSource {
 public:
  virtual ~ByteSource() = default;
  virtual uint64_t size() const = 0;
  // Copies bytes [offset, offset + size) to out; truncated() past the end, ioError() when the
  // system fails. Messages name no file: callers add that context once.
  virtual Status readAt(uint64_t offset, void* out, size_t size) = 0;
};

// A regular file (or anything that can seek), opened for reading; it must not change while
// open (small reads are served from a window read once, and a group checked once is trusted).
Result<std::unique_ptr<ByteSource>> openFileSource(const std::string& path);
// `data` is read in place: it must outlive the source and not change.
std::unique_ptr<ByteSource> memorySource(const void* data, size_t size);

}  // namespace animc
