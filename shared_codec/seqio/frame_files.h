// SPDX-License-Identifier: Apache-2.0
// Sequences stored as one file per frame (the frame-file formats of sequence_formats.h):
// listing them (a directory, a .txt list, a numbered pattern) and streaming them with the
// checks that every frame shares frame 0's connectivity.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/sequence.h"

namespace animc {

// A frame file and, for an entry of a .txt list, where it is listed ("list.txt line 3"), so
// that an error in the frame names the line to fix.
struct FrameFile {
  std::string path;
  std::string listed_at;  // empty for the files of a folder or a lone frame
};

// The same files, listed nowhere.
std::vector<FrameFile> unlistedFrameFiles(const std::vector<std::string>& paths);

// "frame2" before "frame10": digit runs compare by value (then by length, then plain order).
bool naturalLess(const std::string& a, const std::string& b);

// The frame files of `dir` (not hidden ones, any frame-file format), in natural order of
// their names.
Result<std::vector<std::string>> listFrameDirectory(const std::string& dir);

// Whether `path` names no file and its file name has a '%': a numbered pattern, or a mistyped
// one.
bool isFramePattern(const std::string& path);

// A numbered pattern: a frame file's name with "%d" or "%0Nd" where the frame number stands,
// printf's way ("walk/frame_%04d.obj": frame_0000.obj, frame_0001.obj, ...; a number wider
// than N is written in full). The files of its folder that match, in the order of their
// numbers, which must follow each other without a gap from the lowest one there.
Result<std::vector<std::string>> listNumberedFrames(const std::string& pattern);

// The frames of a .txt list, relative paths resolved against the list's directory.
Result<std::vector<FrameFile>> readFrameList(const std::string& list_path);

// Reads frame 0 now (the topology must be known up front). `reference` (may be null) is a
// mesh the frames must match; `reference_name` names it in messages. Messages about a frame
// start with where it is listed, if it is, then its path.
Result<std::unique_ptr<FrameSource>> openFrameFiles(std::vector<FrameFile> frames,
                                                    const Topology* reference,
                                                    const std::string& reference_name);

}  // namespace animc
