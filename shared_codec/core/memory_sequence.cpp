// SPDX-License-Identifier: Apache-2.0
#include "core/memory_sequence.h"

#include <new>

namespace animc {

Result<std::vector<std::vector<float>>> readFrames(FrameSource& source, int64_t max_frames) {
  std::vector<std::vector<float>> frames;
  try {
    while (int64_t(frames.size()) < max_frames) {
      std::vector<float> xyz;
      ANIMC_ASSIGN_OR_RETURN(bool more, source.next(xyz));
      if (!more) break;
      frames.push_back(std::move(xyz));
    }
  } catch (const std::bad_alloc&) {
    return limitExceeded(source.where() + ": not enough memory to hold the whole sequence");
  }
  return frames;
}

Result<MemorySequence> readAll(FrameSource& source) {
  ANIMC_ASSIGN_OR_RETURN(std::vector<std::vector<float>> frames, readFrames(source));
  return MemorySequence(source.topology(), std::move(frames), source.frameRate(), source.where());
}

}  // namespace animc
