// SPDX-License-Identifier: Apache-2.0
// The temporary files and folders this process has made and not yet renamed into place or
// removed (core/atomic_file.h names them), kept where a signal handler can find them: a fixed
// table of fixed-size buffers, so that removing them allocates nothing and calls only
// async-signal-safe functions. The library never installs a signal handler; a program that
// wants an interrupted run to leave no temporaries behind installs one that calls
// removeRegisteredTemporaries() (animc does, for SIGINT, SIGTERM and SIGHUP).
#pragma once
#include <cstddef>
#include <string>

namespace animc {

enum class TemporaryKind { kFile, kFolder };

// Temporaries registered at once (a decode to frames has two: its folder and the frame being
// written), and the longest path a slot holds, in bytes.
constexpr int kMaxTemporaries = 64;
constexpr size_t kMaxTemporaryPathBytes = 4095;

// Records a temporary (as an absolute path, so a later chdir does not matter). Returns its slot
// for unregisterTemporary(), or -1 when every slot is taken or the path is too long: that
// temporary is then removed by its owner only, not by removeRegisteredTemporaries().
int registerTemporary(const std::string& path, TemporaryKind kind);

// Forgets a slot once its temporary is renamed into place or removed; -1 is ignored.
void unregisterTemporary(int slot);

// Removes every registered temporary: files are unlinked, folders emptied of their files and
// removed. Async-signal-safe (atomics, open, getdents64, unlinkat, close, rmdir, unlink); a
// temporary being registered or unregistered at that instant may be missed.
void removeRegisteredTemporaries();

}  // namespace animc
