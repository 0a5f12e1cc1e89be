// SPDX-License-Identifier: Apache-2.0
// Sequential byte sources for the sequence readers: a plain file, or an .xz file decompressed
// on the fly with liblzma so that a large point cache never sits whole in memory.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/status.h"

namespace animc {

class ByteInput {
 public:
  virtual ~ByteInput() = default;
  // Reads up to `size` bytes; returns fewer only at the end of the data.
  virtual Result<size_t> read(void* dst, size_t size) = 0;
  // Total (decompressed) size, or -1 when it cannot be known without reading everything.
  virtual int64_t size() const = 0;
};

// Opens `path`; names ending in ".xz" (any case) are decompressed while reading.
Result<std::unique_ptr<ByteInput>> openByteInput(const std::string& path);

// Reads a whole (uncompressed) file: single meshes, list files, and the .ams that `animc bench`
// decodes from memory.
Result<std::vector<uint8_t>> readWholeFile(const std::string& path);

// Case-insensitive "does name end with suffix".
bool endsWithNoCase(const std::string& name, const std::string& suffix);

}  // namespace animc
