// SPDX-License-Identifier: Apache-2.0
#include "core/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#ifdef _WIN32
#include <io.h>
#include <process.h>
#else
#include <unistd.h>
#endif

namespace animc {
namespace {

long processId() {
#ifdef _WIN32
  return static_cast<long>(_getpid());
#else
  return static_cast<long>(getpid());
#endif
}


bool syncToDisk(std::FILE* file) {
#ifdef _WIN32
  return _commit(_fileno(file)) == 0;
#else
  return fsync(fileno(file)) == 0;
#endif
}

// Why the temporary beside `path` could not be created, under the name the user gave: the
// temporary's name means nothing to them.
Status creationError(const std::string& path, const std::string& temp_path, int error) {
  std::string folder = std::filesystem::path(temp_path).parent_path().string();
  if (folder.empty()) folder = ".";
  if (error == ENOENT) return ioError(path + ": no such directory " + folder);
  if (error == ENOTDIR) return ioError(path + ": " + folder + " is not a directory");
  return ioError(path + ": cannot create a file in " + folder + ": " + std::strerror(error));
}

}  // namespace

// The counter is shared by every temporary of the process (threads, retries, several targets).
std::string temporaryPathBeside(const std::string& path) {
  static std::atomic<uint64_t> counter{0};
  std::string named = path;
  while (named.size() > 1 && named.back() == '/') named.pop_back();
  const std::string name =
      ".animc-" + std::to_string(processId()) + "-" + std::to_string(counter++) + ".tmp";
  return (std::filesystem::path(named).parent_path() / name).string();
}

AtomicFile::~AtomicFile() { abandon(); }

Status AtomicFile::open(const std::string& path) {
  if (file_) return invalidArgument(path + ": AtomicFile is already open for " + path_);
  path_ = path;
  failed_ = false;
  // "x": never truncate a file already there (a leftover of an earlier process that had the
  // same id); take the next name instead.
  for (int attempt = 0; attempt < 100 && !file_; ++attempt) {
    temp_path_ = temporaryPathBeside(path);
    file_ = std::fopen(temp_path_.c_str(), "wbx");
    if (!file_ && errno != EEXIST) break;
  }
  if (!file_) return creationError(path, temp_path_, errno);
  return Status();
}

Status AtomicFile::fail(const char* what) {
  failed_ = true;
  return ioError(path_ + ": " + what + " failed: " + std::strerror(errno));
}

Status AtomicFile::write(const void* data, size_t size) {
  if (!file_) return invalidArgument(path_ + ": write to a closed AtomicFile");
  if (size == 0) return Status();
  if (std::fwrite(data, 1, size, file_) != size) return fail("write");
  return Status();
}

Status AtomicFile::seek(uint64_t offset) {
  if (!file_) return invalidArgument(path_ + ": seek in a closed AtomicFile");
#ifdef _WIN32
  int rc = _fseeki64(file_, static_cast<__int64>(offset), SEEK_SET);
#else
  int rc = fseeko(file_, static_cast<off_t>(offset), SEEK_SET);
#endif
  if (rc != 0) return fail("seek");
  return Status();
}

uint64_t AtomicFile::tell() const {
  if (!file_) return 0;
#ifdef _WIN32
  __int64 pos = _ftelli64(file_);
#else
  off_t pos = ftello(file_);
#endif
  return pos < 0 ? 0 : static_cast<uint64_t>(pos);
}

Status AtomicFile::commit(Sync sync) {
  if (!file_) return invalidArgument(path_ + ": commit of a closed AtomicFile");
  if (failed_) {
    abandon();
    return ioError(path_ + ": not committed because an earlier write failed");
  }
  // Remember the first failure's errno: fclose must run even after a failed flush.
  int error = 0;
  if (std::fflush(file_) != 0 || (sync == Sync::kFsync && !syncToDisk(file_))) error = errno;
  if (std::fclose(file_) != 0 && error == 0) error = errno;
  file_ = nullptr;
  if (error != 0) {
    std::remove(temp_path_.c_str());
    return ioError(path_ + ": flushing failed: " + std::strerror(error));
  }
  // std::filesystem::rename replaces an existing target on every platform.
  std::error_code ec;
  std::filesystem::rename(temp_path_, path_, ec);
  if (ec) {
    std::remove(temp_path_.c_str());
    return ioError(path_ + ": cannot rename " + temp_path_ + " over it: " + ec.message());
  }
  return Status();
}

void AtomicFile::abandon() {
  if (!file_) return;
  std::fclose(file_);
  file_ = nullptr;
  std::remove(temp_path_.c_str());
}

}  // namespace animc
