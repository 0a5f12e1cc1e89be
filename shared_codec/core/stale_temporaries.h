// SPDX-License-Identifier: Apache-2.0
// Leftovers of killed runs. A run killed by a signal no handler can catch (SIGKILL, the
// out-of-memory killer, a power cut) leaves its named temporaries behind: a decode to a frame
// folder always has one (the folder it fills before swapping it in), a file output only where
// the file system has no O_TMPFILE. They are named ".animc-<pid>-<n>.tmp" (core/atomic_file.h),
// and the next output written into the same folder removes them.
#pragma once
#include <string>

namespace animc {

// A leftover is removed only when all of these hold, so that nothing another run is still
// writing, and nothing animcompress did not write, is touched:
// - its name is ".animc-<pid>-<n>.tmp" and no process <pid> exists on this machine;
// - it has not been modified for kStaleTemporarySeconds (a run on another machine sharing
//   the folder writes a frame or a block far more often);
// - it is a regular file, or a folder holding only regular files named as this library's
//   frames ("frame_<n>.ply", ".off", ... in any frame-file format) or temporaries.
// Best effort: a leftover that cannot be removed is left, silently. Returns how many were.
constexpr long kStaleTemporarySeconds = 600;
int removeStaleTemporaries(const std::string& folder);

// Whether `name` (a file name, no folder) has the form of a named temporary; sets *pid.
bool isTemporaryName(const std::string& name, long* pid);

}  // namespace animc
