// SPDX-License-Identifier: Apache-2.0
#include "core/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/stale_temporaries.h"
#include "core/temp_registry.h"

namespace animc {
namespace {

// Why the temporary beside `path` could not be created, under the name the user gave: the
// temporary's name means nothing to them.
Status creationError(const std::string& path, const std::string& temp_path, int error) {
  std::string folder = std::filesystem::path(temp_path).parent_path().string();
  if (folder.empty()) folder = ".";
  if (error == ENOENT) return ioError(path + ": no such directory " + folder);
  if (error == ENOTDIR) return ioError(path + ": " + folder + " is not a directory");
  return ioError(path + ": cannot create a file in " + folder + ": " + std::strerror(error));
}

// Writes all of `size` bytes to `fd`; 0 or the errno of the failure.
int writeAll(int fd, const char* data, size_t size) {
  for (size_t done = 0; done < size;) {
    const ssize_t n = ::write(fd, data + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return errno;
    done += size_t(n);
  }
  return 0;
}

// Copies the whole spool, from its start, to `fd`; 0 or the errno of the failure.
int copySpool(std::FILE* spool, int fd) {
  if (fseeko(spool, 0, SEEK_SET) != 0) return errno;
  char buffer[1 << 16];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, spool)) > 0;)
    if (int error = writeAll(fd, buffer, n)) return error;
  return std::ferror(spool) ? EIO : 0;
}

std::atomic<bool> unnamed_temporaries{true};

// Linux's own limit on links followed in one path (MAXSYMLINKS).
constexpr int kMaxLinkHops = 40;

}  // namespace

Result<std::string> replacedPath(const std::string& path) {
  std::string target = path;
  for (int hops = 0; hops <= kMaxLinkHops; ++hops) {
    struct stat st;
    if (lstat(target.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return target;
    std::error_code ec;
    const std::filesystem::path link = std::filesystem::read_symlink(target, ec);
    if (ec) return ioError(path + ": cannot read the symbolic link " + target + ": " + ec.message());
    target = link.is_absolute() ? link.string()
                                : (std::filesystem::path(target).parent_path() / link).string();
  }
  return ioError(path + ": too many levels of symbolic links");
}

// The counter is shared by every temporary of the process (threads, retries, several targets).
std::string temporaryPathBeside(const std::string& path) {
  static std::atomic<uint64_t> counter{0};
  std::string named = path;
  while (named.size() > 1 && named.back() == '/') named.pop_back();
  const std::string name =
      ".animc-" + std::to_string(getpid()) + "-" + std::to_string(counter++) + ".tmp";
  return (std::filesystem::path(named).parent_path() / name).string();
}

void setUnnamedTemporaries(bool enabled) { unnamed_temporaries = enabled; }

Status writeFileAtomically(const std::string& path, const void* data, size_t size) {
  AtomicFile file;
  ANIMC_RETURN_IF_ERROR(file.open(path));
  ANIMC_RETURN_IF_ERROR(file.write(data, size));
  return file.commit();
}

AtomicFile::~AtomicFile() { abandon(); }

Status AtomicFile::open(const std::string& path) {
  if (file_) return invalidArgument(path + ": AtomicFile is already open for " + path_);
  path_ = path;
  failed_ = false;
  position_ = 0;
  // stat() follows links, so a link to a device (/dev/stdout) is written in place too.
  struct stat st;
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    return openInPlace(S_ISDIR(st.st_mode));
  ANIMC_ASSIGN_OR_RETURN(target_, replacedPath(path));
  return createTemporary();
}

Status AtomicFile::createTemporary() {
  mode_ = Mode::kReplace;
  temp_path_.clear();
  // Not inside a temporary folder of ours (the frames of a decode to a folder): its parent
  // was cleaned when the folder was made, and a scan per frame would cost frames^2.
  const std::filesystem::path folder = std::filesystem::path(target_).parent_path();
  if (!isTemporaryName(folder.filename().string(), nullptr)) removeStaleTemporaries(folder.string());
  if (openUnnamed()) return Status();
  return createNamedTemporary();
}

// An unnamed file in the target's folder (O_TMPFILE): a process killed before commit() leaves
// nothing behind, not even after SIGKILL. False where the file system or kernel lacks it, or
// the folder is not there (createNamedTemporary() then says why).
bool AtomicFile::openUnnamed() {
#ifdef O_TMPFILE
  if (!unnamed_temporaries) return false;
  std::string folder = std::filesystem::path(target_).parent_path().string();
  if (folder.empty()) folder = ".";
  const int fd = ::open(folder.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0666);
  if (fd < 0) return false;
  file_ = fdopen(fd, "w+b");
  if (file_) return true;
  ::close(fd);
#endif
  return false;
}

Status AtomicFile::createNamedTemporary() {
  // "x": never truncate a file already there (a leftover of an earlier process that had the
  // same id); take the next name instead.
  // Registered before it is created, so that a signal arriving in between still finds it.
  for (int attempt = 0; attempt < 100 && !file_; ++attempt) {
    temp_path_ = temporaryPathBeside(target_);
    temp_slot_ = registerTemporary(temp_path_, TemporaryKind::kFile);
    file_ = std::fopen(temp_path_.c_str(), "wbx");
    if (file_) break;
    const int error = errno;
    unregisterTemporary(temp_slot_);
    temp_slot_ = -1;
    if (error != EEXIST) return creationError(path_, temp_path_, error);
  }
  if (!file_) return creationError(path_, temp_path_, EEXIST);
  return Status();
}

// The unnamed file gets a temporary name beside the target, to be renamed over it: a link to
// it where /proc is mounted, else a named copy.
Status AtomicFile::nameUnnamed() {
  if (std::fflush(file_) != 0) return fail("write");
  const std::string open_file = "/proc/self/fd/" + std::to_string(fileno(file_));
  for (int attempt = 0; attempt < 100; ++attempt) {
    temp_path_ = temporaryPathBeside(target_);
    temp_slot_ = registerTemporary(temp_path_, TemporaryKind::kFile);
    if (linkat(AT_FDCWD, open_file.c_str(), AT_FDCWD, temp_path_.c_str(), AT_SYMLINK_FOLLOW) == 0)
      return Status();
    const int error = errno;
    unregisterTemporary(temp_slot_);
    temp_slot_ = -1;
    if (error != EEXIST) break;
  }
  std::FILE* unnamed = file_;
  file_ = nullptr;
  temp_path_.clear();
  Status s = createNamedTemporary();
  if (s.ok()) {
    errno = copySpool(unnamed, fileno(file_));
    if (errno != 0) s = fail("copying the unnamed temporary");
  }
  std::fclose(unnamed);
  return s;
}

void AtomicFile::removeTemporary() {
  if (!temp_path_.empty()) std::remove(temp_path_.c_str());
  unregisterTemporary(temp_slot_);
  temp_slot_ = -1;
}

Status AtomicFile::openInPlace(bool is_directory) {
  if (is_directory) return ioError(path_ + ": is a directory");
  temp_path_.clear();
  const int fd = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return ioError(path_ + ": cannot open for writing: " + std::strerror(errno));
  if (lseek(fd, 0, SEEK_CUR) >= 0) {
    mode_ = Mode::kInPlace;
    file_ = fdopen(fd, "wb");
  } else {
    // Writers seek back to patch headers, which a FIFO or a terminal cannot do: the bytes
    // gather in an unnamed file (nothing to leave behind) and go out in commit().
    mode_ = Mode::kSpooled;
    file_ = std::tmpfile();
    in_place_fd_ = fd;
  }
  if (file_) return Status();
  const int error = errno;
  ::close(fd);
  in_place_fd_ = -1;
  return ioError(path_ + ": cannot write to it: " + std::strerror(error));
}

Status AtomicFile::fail(const char* what) {
  failed_ = true;
  return ioError(path_ + ": " + what + " failed: " + std::strerror(errno));
}

Status AtomicFile::write(const void* data, size_t size) {
  if (!file_) return invalidArgument(path_ + ": write to a closed AtomicFile");
  if (size == 0) return Status();
  if (std::fwrite(data, 1, size, file_) != size) return fail("write");
  position_ += size;
  return Status();
}

Status AtomicFile::seek(uint64_t offset) {
  if (!file_) return invalidArgument(path_ + ": seek in a closed AtomicFile");
  if (fseeko(file_, static_cast<off_t>(offset), SEEK_SET) != 0) return fail("seek");
  position_ = offset;
  return Status();
}

uint64_t AtomicFile::tell() const { return file_ ? position_ : 0; }

// Flushes, copies out a spool and closes everything open; 0 or the errno of the first
// failure (the closes run even after one).
int AtomicFile::closeAll(Sync sync) {
  int error = 0;
  if (std::fflush(file_) != 0) error = errno;
  if (error == 0 && mode_ == Mode::kSpooled) error = copySpool(file_, in_place_fd_);
  // A device has no disk to sync; only a temporary about to be renamed is.
  if (error == 0 && sync == Sync::kFsync && mode_ == Mode::kReplace && fsync(fileno(file_)) != 0)
    error = errno;
  if (std::fclose(file_) != 0 && error == 0) error = errno;
  file_ = nullptr;
  if (in_place_fd_ >= 0 && ::close(in_place_fd_) != 0 && error == 0) error = errno;
  in_place_fd_ = -1;
  return error;
}

Status AtomicFile::commit(Sync sync) {
  if (!file_) return invalidArgument(path_ + ": commit of a closed AtomicFile");
  if (failed_) {
    abandon();
    return ioError(path_ + ": not committed because an earlier write failed");
  }
  if (mode_ == Mode::kReplace && temp_path_.empty()) {
    const Status named = nameUnnamed();
    if (!named.ok()) {
      abandon();
      return named;
    }
  }
  const int error = closeAll(sync);
  if (error != 0) {
    if (mode_ == Mode::kReplace) removeTemporary();
    return ioError(path_ + ": flushing failed: " + std::strerror(error));
  }
  if (mode_ != Mode::kReplace) return Status();
  std::error_code ec;
  std::filesystem::rename(temp_path_, target_, ec);
  if (ec) {
    removeTemporary();
    const std::string over = target_ == path_ ? "it" : target_;
    return ioError(path_ + ": cannot rename " + temp_path_ + " over " + over + ": " + ec.message());
  }
  // Only now: a signal before the rename must still find the temporary.
  unregisterTemporary(temp_slot_);
  temp_slot_ = -1;
  return Status();
}

void AtomicFile::abandon() {
  if (!file_) return;
  std::fclose(file_);
  file_ = nullptr;
  if (in_place_fd_ >= 0) ::close(in_place_fd_);
  in_place_fd_ = -1;
  if (mode_ == Mode::kReplace) removeTemporary();
}

}  // namespace animc
