// SPDX-License-Identifier: Apache-2.0
// PC2 point caches (3ds Max / Blender): little-endian, 32-byte header
//   char magic[12] = "POINTCACHE2\0"; int32 version = 1; int32 points;
//   float32 start_frame; float32 sample_rate; int32 samples;
// then `samples` frames of `points` float32 x y z.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "core/sequence.h"

namespace animc {

// `path` may end in .xz (streamed). The mesh gives the connectivity; `mesh_name` is its file.
Result<std::unique_ptr<FrameSource>> openPc2(const std::string& path, const Topology& topology,
                                             const std::string& mesh_name);

Result<std::unique_ptr<FrameSink>> createPc2Sink(const std::string& path, uint32_t point_count,
                                                 int64_t frame_count);

}  // namespace animc
