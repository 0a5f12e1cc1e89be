// SPDX-License-Identifier: Apache-2.0
#include "core/stale_temporaries.h"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>

#include "seqio/sequence_formats.h"

namespace animc {
namespace fs = std::filesystem;
namespace {

// Digits only, at least one; returns the position after them, or npos.
size_t skipDigits(const std::string& s, size_t at, long* value) {
  const size_t start = at;
  long v = 0;
  while (at < s.size() && s[at] >= '0' && s[at] <= '9' && at - start < 12) v = v * 10 + (s[at++] - '0');
  if (at == start || (at < s.size() && s[at] >= '0' && s[at] <= '9')) return std::string::npos;
  if (value) *value = v;
  return at;
}

bool isFrameName(const std::string& name) {
  constexpr const char* kPrefix = "frame_";
  if (name.compare(0, std::strlen(kPrefix), kPrefix) != 0) return false;
  const size_t end = skipDigits(name, std::strlen(kPrefix), nullptr);
  if (end == std::string::npos) return false;
  const SequenceFormatSpec* format = frameFileFormatOf(name);
  return format && name.substr(end) == format->extension;
}

bool processGone(long pid) {
  return pid > 0 && pid != long(getpid()) && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH;
}

bool oldEnough(const struct stat& st) {
  return std::time(nullptr) - st.st_mtime >= kStaleTemporarySeconds;
}

// A folder of our frames and temporaries only (checked without following links).
bool holdsOnlyOurFiles(const std::string& folder) {
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!it->is_regular_file(ec) || it->is_symlink(ec)) return false;
    if (!isFrameName(name) && !isTemporaryName(name, nullptr)) return false;
  }
  return !ec;
}

bool removeLeftover(const std::string& path) {
  struct stat st;
  if (::lstat(path.c_str(), &st) != 0 || !oldEnough(st)) return false;
  std::error_code ec;
  if (S_ISREG(st.st_mode)) return fs::remove(path, ec);
  if (!S_ISDIR(st.st_mode) || !holdsOnlyOurFiles(path)) return false;
  return fs::remove_all(path, ec) > 0 && !ec;
}

}  // namespace

bool isTemporaryName(const std::string& name, long* pid) {
  constexpr const char* kPrefix = ".animc-";
  constexpr const char* kSuffix = ".tmp";
  if (name.compare(0, std::strlen(kPrefix), kPrefix) != 0) return false;
  size_t at = skipDigits(name, std::strlen(kPrefix), pid);
  if (at == std::string::npos || at >= name.size() || name[at] != '-') return false;
  at = skipDigits(name, at + 1, nullptr);
  return at != std::string::npos && name.compare(at, std::string::npos, kSuffix) == 0;
}

int removeStaleTemporaries(const std::string& folder) {
  int removed = 0;
  std::error_code ec;
  const fs::path where = folder.empty() ? fs::path(".") : fs::path(folder);
  for (fs::directory_iterator it(where, ec), end; !ec && it != end; it.increment(ec)) {
    long pid = 0;
    if (isTemporaryName(it->path().filename().string(), &pid) && processGone(pid))
      removed += removeLeftover(it->path().string());
  }
  return removed;
}

}  // namespace animc
