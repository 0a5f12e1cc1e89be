// SPDX-License-Identifier: GPL-3.0-or-later
// Small glue both plugins need between MeshLab's callbacks and the codec library's.
#pragma once
#include <functional>
#include <string>

#include <cstring>  // wrap/callback.h uses strcpy without including it
#include <wrap/callback.h>

#include "core/sequence.h"

namespace animc::meshlab {

using LogFn = std::function<void(const std::string& line)>;

// Logs each line of a multi-line text separately (MeshLab's log shows one entry per call).
void logLines(const LogFn& log, const std::string& text);

// The exception being handled, as a one-line reason, for a catch (...) at a plugin's entry
// point: MeshLab 2020.09's meshlabserver catches nothing and its GUI only std::bad_alloc, so an
// exception that escapes a plugin ends the program.
std::string currentExceptionMessage();

// MeshLab's progress callback (its progress bar) as the codec library's; null stays empty.
ProgressFn progressFrom(vcg::CallBackPos* cb);

}  // namespace animc::meshlab
