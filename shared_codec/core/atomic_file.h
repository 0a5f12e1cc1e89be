// SPDX-License-Identifier: Apache-2.0
// Writes a file so that readers only ever see the old content or the complete new content:
// data goes to a temporary file in the target's folder and commit() renames it over the target.
// Where the file system has O_TMPFILE (Linux: ext4, xfs, btrfs, tmpfs, ...) the temporary has
// no name until commit() links it in, so a process killed while writing, SIGKILL included,
// leaves nothing behind. A named temporary (elsewhere, and during commit()) that is never
// committed (error, early return) is removed by the destructor, and while it exists it is
// registered (core/temp_registry.h) for a signal handler.
//
// Temporary names: every named temporary file or folder animcompress creates is named
// ".animc-<pid>-<n>.tmp" (<pid> the process id, <n> a counter), in the folder of the file it
// stands for, so that a leftover of a killed run matches the fixed pattern ".animc-*.tmp".
// The name does not grow with the target's, so every valid target name works (a suffix on the
// target's name made names of 244 to 255 bytes "too long").
//
// A target that exists and is not a regular file (a character device such as /dev/null, a
// FIFO) has no old content to keep whole, and renaming over it would replace it with a regular
// file: it is opened and written in place, never renamed over. If it cannot seek (a FIFO, a
// terminal), the bytes gather in an unnamed temporary file and commit() copies them to it,
// because writers seek back to patch headers. A folder is refused.
//
// A symbolic link stays a link: the file it points to (through every link) is the one
// replaced, with the temporary beside that file, so that the rename stays on its file system.
// A dangling link names the file to create.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>

#include "core/status.h"

namespace animc {

// A new temporary name ".animc-<pid>-<n>.tmp" in the folder that holds `path` (a file, or a
// folder with or without a trailing '/'): on the same file system, so it can be renamed there.
std::string temporaryPathBeside(const std::string& path);

// The path a write to `path` replaces: `path`, or for a symbolic link what it points to,
// through every link (relative links resolved against their own folder); an error for a loop.
Result<std::string> replacedPath(const std::string& path);

// Whether AtomicFile makes unnamed temporaries where it can (the default) or always named ones,
// as on a file system without O_TMPFILE: for tests of that path. Process-wide.
void setUnnamedTemporaries(bool enabled);

// The whole of a file held in memory, written through an AtomicFile.
Status writeFileAtomically(const std::string& path, const void* data, size_t size);

class AtomicFile {
 public:
  enum class Sync { kNone, kFsync };  // kFsync: flush to disk before the rename

  AtomicFile() = default;
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // Creates the temporary file beside `path` (or opens `path` itself if it is a device or
  // FIFO); fails if one is already open.
  Status open(const std::string& path);
  Status write(const void* data, size_t size);
  // Moves the write position (to patch a header once the counts are known).
  Status seek(uint64_t offset);
  uint64_t tell() const;
  // Flushes, closes and renames the temporary over the target; the object is then closed.
  Status commit(Sync sync = Sync::kNone);
  // Closes and deletes the temporary without touching the target (what was already written
  // to a device in place stays written).
  void abandon();

  bool isOpen() const { return file_ != nullptr; }
  const std::string& path() const { return path_; }

 private:
  // kReplace: a temporary renamed over the target; kInPlace: the target itself (a seekable
  // device); kSpooled: an unnamed file copied to in_place_fd_ (a FIFO, a terminal).
  enum class Mode { kReplace, kInPlace, kSpooled };

  Status createTemporary();
  bool openUnnamed();
  Status createNamedTemporary();
  Status nameUnnamed();
  Status openInPlace(bool is_directory);
  int closeAll(Sync sync);
  void removeTemporary();
  Status fail(const char* what);

  std::FILE* file_ = nullptr;
  Mode mode_ = Mode::kReplace;
  int in_place_fd_ = -1;
  std::string path_;
  std::string target_;  // path_, or the file its symbolic links lead to
  std::string temp_path_;  // empty while the temporary has no name (O_TMPFILE)
  int temp_slot_ = -1;  // in the registry of temporaries
  // Counted here rather than asked of the stream: a device such as /dev/null reports 0.
  uint64_t position_ = 0;
  bool failed_ = false;  // a write or seek failed: commit() must refuse
};

}  // namespace animc
