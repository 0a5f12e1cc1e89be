// SPDX-License-Identifier: Apache-2.0
// Writes a sequence as a directory of frame files, frame_00000.<ext>, frame_00001.<ext>, ...
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "core/sequence.h"
#include "seqio/sequence_io.h"

namespace animc {

// `format` is a frame-file format (sequence_formats.h). Frames are written into a temporary folder beside `dir`
// (".animc-<pid>-<n>.tmp", core/atomic_file.h), which finish() puts in place of `dir` as a
// whole: a reader of `dir`
// sees its old content or every new frame, never a mix, and a sink destroyed before finish()
// (a decode that failed late) leaves `dir` as it was. A non-empty `dir` is refused unless
// `existing` is kReplace, which replaces the folder with everything in it.
Result<std::unique_ptr<FrameSink>> createFrameDirSink(const std::string& dir, SequenceFormat format,
                                                      const Topology& topology, int64_t frame_count,
                                                      ExistingOutput existing);

// "frame_00042.ply"
std::string frameFileName(int64_t index, SequenceFormat format);

}  // namespace animc
