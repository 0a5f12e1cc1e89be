// SPDX-License-Identifier: Apache-2.0
// Whether two paths name one file, by identity (device and inode) rather than by name, so that
// "./in.pc2", a hard link or a symbolic link to it all count as the same file.
#pragma once
#include <string>
#include <vector>

#include "core/status.h"

namespace animc {

// True when both paths exist and are the same file.
bool sameFile(const std::string& a, const std::string& b);

// An error naming the input when `output` is an existing file that is also one of `inputs`:
// writing it would destroy that input (the write replaces it before anything reads it again).
Status refuseOutputOverInput(const std::string& output, const std::vector<std::string>& inputs);

}  // namespace animc
