// SPDX-License-Identifier: GPL-3.0-or-later
#include "frame_range_parameters.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>

namespace animc::meshlab {

void addFrameRangeParameters(RichParameterList& par) {
  par.addParam(RichInt("FirstFrame", 0, "First frame", "First frame to load as a layer (0 = the first)."));
  par.addParam(RichInt("LastFrame", -1, "Last frame", "Last frame to load; -1 = the last frame of the file."));
}

namespace {

// The value of environment variable `name` when it is a positive integer, else 0.
uint64_t positiveFromEnvironment(const char* name) {
  const char* env = std::getenv(name);
  if (env == nullptr || *env == '\0') return 0;
  char* end = nullptr;
  const unsigned long long value = std::strtoull(env, &end, 10);
  return *end == '\0' && *env != '-' ? value : 0;
}

constexpr uint64_t kMillion = 1000000;

// WorkLimitMVF shows the limit in millions; left at its default, the exact default applies.
int defaultWorkLimitMillions() {
  return int(std::min<uint64_t>((defaultMaxVertexFrames() + kMillion / 2) / kMillion, INT32_MAX));
}

}  // namespace

void addLimitParameters(RichParameterList& par) {
  par.addParam(RichInt("MemoryLimitMB", int(defaultMemoryLimitMegabytes()), "Memory limit (MB)",
                       "The most memory the new layers may take: a range that needs more is refused "
                       "before anything is loaded. Raise it to load more frames at once."));
  par.addParam(RichInt("WorkLimitMVF", defaultWorkLimitMillions(), "Decode work limit (million vertex-frames)",
                       "The most vertices times frames decoding may cost, counted from the start of the "
                       "frame group holding the first frame: a range that costs more is refused before "
                       "anything is decoded. Raise it for trusted files with long frame groups."));
}

int64_t defaultMemoryLimitMegabytes() {
  const uint64_t mb = positiveFromEnvironment("ANIMC_MEMORY_LIMIT_MB");
  return mb > 0 && mb <= uint64_t(INT32_MAX) ? int64_t(mb) : AmsImport().max_layer_megabytes;
}

uint64_t defaultMaxVertexFrames() {
  const uint64_t vertex_frames = positiveFromEnvironment("ANIMC_MAX_VERTEX_FRAMES");
  return vertex_frames > 0 ? vertex_frames : AmsImport().max_vertex_frames;
}

AmsImport frameRangeFrom(const RichParameterList& par) {
  AmsImport range;
  range.max_layer_megabytes = defaultMemoryLimitMegabytes();
  range.max_vertex_frames = defaultMaxVertexFrames();
  if (par.hasParameter("FirstFrame")) range.first_frame = par.getInt("FirstFrame");
  if (par.hasParameter("LastFrame")) range.last_frame = par.getInt("LastFrame");
  if (par.hasParameter("MemoryLimitMB")) range.max_layer_megabytes = par.getInt("MemoryLimitMB");
  if (par.hasParameter("WorkLimitMVF") && par.getInt("WorkLimitMVF") != defaultWorkLimitMillions())
    range.max_vertex_frames = uint64_t(std::max(par.getInt("WorkLimitMVF"), 0)) * kMillion;
  return range;
}

}  // namespace animc::meshlab
