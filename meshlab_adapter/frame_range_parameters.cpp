// SPDX-License-Identifier: GPL-3.0-or-later
#include "frame_range_parameters.h"

#include <cstdlib>

namespace animc::meshlab {

void addFrameRangeParameters(RichParameterList& par) {
  par.addParam(RichInt("FirstFrame", 0, "First frame", "First frame to load as a layer (0 = the first)."));
  par.addParam(RichInt("LastFrame", -1, "Last frame", "Last frame to load; -1 = the last frame of the file."));
}

void addMemoryLimitParameter(RichParameterList& par) {
  par.addParam(RichInt("MemoryLimitMB", int(defaultMemoryLimitMegabytes()), "Memory limit (MB)",
                       "The most memory the new layers may take: a range that needs more is refused "
                       "before anything is loaded. Raise it to load more frames at once."));
}

int64_t defaultMemoryLimitMegabytes() {
  const char* env = std::getenv("ANIMC_MEMORY_LIMIT_MB");
  char* end = nullptr;
  const long long mb = env != nullptr ? std::strtoll(env, &end, 10) : 0;
  return env != nullptr && *env != '\0' && *end == '\0' && mb > 0 ? mb : AmsImport().max_layer_megabytes;
}

AmsImport frameRangeFrom(const RichParameterList& par) {
  AmsImport range;
  range.max_layer_megabytes = defaultMemoryLimitMegabytes();
  if (par.hasParameter("FirstFrame")) range.first_frame = par.getInt("FirstFrame");
  if (par.hasParameter("LastFrame")) range.last_frame = par.getInt("LastFrame");
  if (par.hasParameter("MemoryLimitMB")) range.max_layer_megabytes = par.getInt("MemoryLimitMB");
  return range;
}

}  // namespace animc::meshlab
