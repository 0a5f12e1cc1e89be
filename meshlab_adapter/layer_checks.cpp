// SPDX-License-Identifier: Apache-2.0
#include "layer_checks.h"

#include <algorithm>
#include <cstdint>

namespace animc::meshlab {
uint64_t layerBytes(const Topology& topology, const LayerElementBytes& element) {
  // The optional attributes MeshLab enables on loaded layers (colour, quality, adjacency) take
  // about as much again as the fixed part of each element.
  constexpr uint64_t kLayerOverhead = 64 << 10;
  return 2 * (uint64_t(topology.vertex_count) * element.vertex + uint64_t(topology.triangles.size()) * element.face) +
         kLayerOverhead;
}

DecoderLimits AmsImport::decoderLimits() const {
  DecoderLimits limits;
  limits.max_output_bytes = uint64_t(std::max<int64_t>(max_layer_megabytes, 0)) << 20;
  limits.max_vertex_frames = max_vertex_frames;
  return limits;
}

Result<FrameRange> planAmsImport(const std::string& path, AmsSource& source, const AmsImport& range,
                                 const LayerElementBytes& element) {
  const int64_t frames = source.frameCount();
  FrameRange r;
  r.first = range.first_frame;
  r.last = range.last_frame < 0 ? frames - 1 : range.last_frame;
  if (r.first < 0 || r.first > r.last || r.last >= frames)
    return invalidArgument("frames " + std::to_string(r.first) + " to " + std::to_string(r.last) +
                           " asked for, but " + path + " has frames 0 to " + std::to_string(frames - 1));
  const uint64_t layers = uint64_t(r.count()), layer = layerBytes(source.topology(), element);
  const uint64_t output = layer > UINT64_MAX / layers ? UINT64_MAX : layers * layer;
  const Status s = source.checkDecodeWork(r.first, r.last + 1, output);
  if (!s.ok()) {  // the library names its own knobs; MeshLab users have these
    const bool memory = s.message().find("max_output_bytes") != std::string::npos;
    return Status(s.code(), s.message() + (memory ? "; in MeshLab: Memory limit (MB) when opening, or "
                                                    "ANIMC_MEMORY_LIMIT_MB"
                                                  : "; in MeshLab: Decode work limit (million vertex-frames) "
                                                    "when opening, or ANIMC_MAX_VERTEX_FRAMES"));
  }
  ANIMC_RETURN_IF_ERROR(source.seek(r.first));
  return r;
}

Status checkLayerCount(const std::string& path, const FrameRange& range, int64_t layers) {
  if (layers == range.count()) return Status();
  return invalidArgument("MeshLab made " + std::to_string(layers) + " layers for " + std::to_string(range.count()) +
                         " frames of " + path);
}

}  // namespace animc::meshlab
