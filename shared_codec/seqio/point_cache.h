// SPDX-License-Identifier: Apache-2.0
// The frame stream shared by PC2 and MDD: after a header, frames of point_count float32
// xyz triples in a fixed byte order. Reading is streamed (one frame buffer), so a cache of
// any length, compressed or not, needs O(points) memory.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/sequence.h"
#include "seqio/byte_input.h"

namespace animc {

struct PointCacheLayout {
  std::string name;  // the file, for messages
  bool big_endian = false;
  int64_t frame_count = 0;
  double frame_rate = 25.0;
};

// `input` is positioned at the first frame; `topology` fixes the point count.
std::unique_ptr<FrameSource> makePointCacheSource(std::unique_ptr<ByteInput> input,
                                                  Topology topology, PointCacheLayout layout);

// Reads exactly `size` header bytes or reports the file as truncated in its header.
Status readHeader(ByteInput& input, const std::string& name, void* dst, size_t size);

// The cache's point count must be the mesh's vertex count.
Status checkPointCount(const std::string& name, int64_t point_count, const Topology& topology,
                       const std::string& mesh_name);

// Checks a seekable input holds exactly `frame_count` frames after `header_bytes`.
Status checkPointCacheSize(const ByteInput& input, const std::string& name, uint64_t header_bytes,
                           int64_t frame_count, uint32_t point_count);

// Writes the header (through `write_header`, which may stream a long one) then the frames,
// atomically; finish() insists on exactly `frame_count` frames.
using HeaderWriter = std::function<Status(AtomicFile& file)>;
Result<std::unique_ptr<FrameSink>> makePointCacheSink(const std::string& path,
                                                      const HeaderWriter& write_header,
                                                      bool big_endian, uint32_t point_count,
                                                      int64_t frame_count);

}  // namespace animc
