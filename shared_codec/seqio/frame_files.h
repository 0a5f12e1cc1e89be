// SPDX-License-Identifier: Apache-2.0
// Sequences stored as one PLY / OFF file per frame: listing them (a directory, a .txt list)
// and streaming them with the checks that every frame shares frame 0's connectivity.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/sequence.h"

namespace animc {

// "frame2" before "frame10": digit runs compare by value (then by length, then plain order).
bool naturalLess(const std::string& a, const std::string& b);

// The .ply / .off files of `dir` (not hidden ones), in natural order of their names.
Result<std::vector<std::string>> listFrameDirectory(const std::string& dir);

// The frame paths of a .txt list, relative ones resolved against the list's directory.
Result<std::vector<std::string>> readFrameList(const std::string& list_path);

// Reads frame 0 now (the topology must be known up front). `reference` (may be null) is a
// mesh the frames must match; `reference_name` names it in messages.
Result<std::unique_ptr<FrameSource>> openFrameFiles(std::vector<std::string> paths,
                                                    const Topology* reference,
                                                    const std::string& reference_name);

}  // namespace animc
