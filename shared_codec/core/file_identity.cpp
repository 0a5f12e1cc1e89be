// SPDX-License-Identifier: Apache-2.0
#include "core/file_identity.h"

#include <sys/stat.h>

namespace animc {

bool sameFile(const std::string& a, const std::string& b) {
  struct stat sa, sb;
  return stat(a.c_str(), &sa) == 0 && stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

Status refuseOutputOverInput(const std::string& output, const std::vector<std::string>& inputs) {
  for (const std::string& input : inputs)
    if (sameFile(output, input))
      return invalidArgument(output + ": is the input " + input +
                             "; writing it would destroy that input (choose another output)");
  return Status();
}

}  // namespace animc
