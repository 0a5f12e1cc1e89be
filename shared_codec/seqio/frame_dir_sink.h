// SPDX-License-Identifier: Apache-2.0
// Writes a sequence as a directory of frame files, frame_00000.<ext>, frame_00001.<ext>, ...
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "core/sequence.h"
#include "seqio/sequence_io.h"

namespace animc {

// `format` is kPly or kOff. Each frame is written atomically as it arrives; finish() removes
// frame files an earlier run left in the directory (frame_<digits>.ply / .off with higher
// numbers or the other extension), and a sink destroyed before finish() deletes the frames
// it wrote.
Result<std::unique_ptr<FrameSink>> createFrameDirSink(const std::string& dir, SequenceFormat format,
                                                      const Topology& topology,
                                                      int64_t frame_count);

// "frame_00042.ply"
std::string frameFileName(int64_t index, SequenceFormat format);

}  // namespace animc
