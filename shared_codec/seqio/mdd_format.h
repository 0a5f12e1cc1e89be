// SPDX-License-Identifier: Apache-2.0
// MDD point caches (LightWave / Blender): big-endian
//   int32 frames; int32 points; float32 times[frames] (seconds);
// then `frames` frames of `points` float32 x y z.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "core/sequence.h"

namespace animc {

// `path` may end in .xz (streamed). The mesh gives the connectivity; `mesh_name` is its file.
Result<std::unique_ptr<FrameSource>> openMdd(const std::string& path, const Topology& topology,
                                             const std::string& mesh_name);

// Frame i gets the time i / frame_rate.
Result<std::unique_ptr<FrameSink>> createMddSink(const std::string& path, uint32_t point_count,
                                                 int64_t frame_count, double frame_rate);

}  // namespace animc
