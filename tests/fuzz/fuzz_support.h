// SPDX-License-Identifier: Apache-2.0
// Shared by the fuzz harnesses: the library reads files by path, so each input is written to
// a per-process scratch file first (several fuzzing jobs may run side by side).
#pragma once
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace animc::fuzz {

// A path in $TMPDIR (or /tmp) ending in `suffix`, unique to this process; readers pick the
// format (and .xz decompression) from the suffix.
inline std::string scratchPath(const std::string& suffix) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir && *dir ? dir : "/tmp") + "/animc_fuzz_" + std::to_string(getpid()) + suffix;
}

// Replaces the scratch file with these bytes; false if the file system refused.
inline bool writeScratch(const std::string& path, const uint8_t* data, size_t size) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  const bool ok = std::fwrite(data, 1, size, f) == size;
  return std::fclose(f) == 0 && ok;
}

}  // namespace animc::fuzz
