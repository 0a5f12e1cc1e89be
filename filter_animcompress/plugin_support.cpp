// SPDX-License-Identifier: GPL-3.0-or-later
#include "plugin_support.h"

#include <sstream>

namespace animc::meshlab {

void logLines(const LogFn& log, const std::string& text) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) log(line);
}

ProgressFn progressFrom(vcg::CallBackPos* cb) {
  if (cb == nullptr) return {};
  return [cb](int percent, const char* what) { return cb(percent, what); };
}

}  // namespace animc::meshlab
