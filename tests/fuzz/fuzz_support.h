// SPDX-License-Identifier: Apache-2.0
// Shared by the fuzz harnesses: the library reads files by path, so each input is written to
// a per-process scratch file first (several fuzzing jobs may run side by side). The scratch
// files and folders are removed when the process exits: a campaign runs many processes.
#pragma once
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace animc::fuzz {

inline std::vector<std::string>& scratchPaths() {
  static std::vector<std::string> paths;
  return paths;
}

inline void removeScratch() {
  std::error_code ignored;
  for (const std::string& path : scratchPaths()) std::filesystem::remove_all(path, ignored);
}

// A path in $TMPDIR (or /tmp) ending in `suffix`, unique to this process; readers pick the
// format (and .xz decompression) from the suffix.
inline std::string scratchPath(const std::string& suffix) {
  const char* dir = std::getenv("TMPDIR");
  const std::string path = std::string(dir && *dir ? dir : "/tmp") + "/animc_fuzz_" + std::to_string(getpid()) + suffix;
  // The list is built before removeScratch is registered, so that it outlives the call.
  std::vector<std::string>& paths = scratchPaths();
  static const bool removed_at_exit = std::atexit(removeScratch) == 0;
  (void)removed_at_exit;
  if (std::find(paths.begin(), paths.end(), path) == paths.end()) paths.push_back(path);
  return path;
}

// Replaces the scratch file with these bytes; false if the file system refused.
inline bool writeScratch(const std::string& path, const uint8_t* data, size_t size) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  const bool ok = std::fwrite(data, 1, size, f) == size;
  return std::fclose(f) == 0 && ok;
}

}  // namespace animc::fuzz
