#include "core/memory_sequence.h"

#include <new>

namespace animc {

Result<MemorySequence> readAll(FrameSource& source) {
  std::vector<std::vector<float>> frames;
  try {
    for (;;) {
      std::vector<float> xyz;
      ANIMC_ASSIGN_OR_RETURN(bool more, source.next(xyz));
      if (!more) break;
      frames.push_back(std::move(xyz));
    }
  } catch (const std::bad_alloc&) {
    return limitExceeded(source.where() + ": not enough memory to hold the whole sequence");
  }
  return MemorySequence(source.topology(), std::move(frames), source.frameRate(), source.where());
}

}  // namespace animc
