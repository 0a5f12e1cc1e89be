// SPDX-License-Identifier: GPL-3.0-or-later
#include "plugin_support.h"

#include <exception>
#include <new>
#include <sstream>

namespace animc::meshlab {

void logLines(const LogFn& log, const std::string& text) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) log(line);
}

std::string currentExceptionMessage() {
  try {
    throw;
  } catch (const std::bad_alloc&) {
    return "out of memory (try fewer frames or layers)";
  } catch (const std::exception& e) {
    return std::string("unexpected error: ") + e.what();
  } catch (...) {
    return "unexpected error";
  }
}

ProgressFn progressFrom(vcg::CallBackPos* cb) {
  if (cb == nullptr) return {};
  return [cb](int percent, const char* what) { return cb(percent, what); };
}

}  // namespace animc::meshlab
