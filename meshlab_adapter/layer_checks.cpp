// SPDX-License-Identifier: Apache-2.0
#include "layer_checks.h"

namespace animc::meshlab {
namespace {

Status checkLayerMemory(const std::string& path, const Topology& topology, const FrameRange& r,
                        int64_t max_megabytes, const LayerElementBytes& element) {
  const double megabytes = double(r.count()) * double(layerBytes(topology, element)) / (1 << 20);
  if (megabytes <= double(max_megabytes)) return Status();
  // Built as a string: a fixed buffer would cut the message at a long path.
  return limitExceeded("frames " + std::to_string(r.first) + " to " + std::to_string(r.last) + " of " + path +
                       " would take about " + std::to_string(int64_t(megabytes + 0.5)) + " MB as layers (" +
                       std::to_string(topology.vertex_count) + " vertices and " +
                       std::to_string(topology.triangles.size()) + " triangles each), above the memory limit of " +
                       std::to_string(max_megabytes) +
                       " MB: load fewer frames (First frame, Last frame) or raise the limit (Memory limit (MB) "
                       "when opening, or ANIMC_MEMORY_LIMIT_MB)");
}

}  // namespace

uint64_t layerBytes(const Topology& topology, const LayerElementBytes& element) {
  // The optional attributes MeshLab enables on loaded layers (colour, quality, adjacency) take
  // about as much again as the fixed part of each element.
  constexpr uint64_t kLayerOverhead = 64 << 10;
  return 2 * (uint64_t(topology.vertex_count) * element.vertex + uint64_t(topology.triangles.size()) * element.face) +
         kLayerOverhead;
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
  ANIMC_RETURN_IF_ERROR(checkLayerMemory(path, source.topology(), r, range.max_layer_megabytes, element));
  const Status work = source.checkDecodeWork(r.first, r.last + 1);
  if (!work.ok())  // the library names its own knobs; MeshLab users have these
    return Status(work.code(), work.message() +
                                   "; in MeshLab: Decode work limit (million vertex-frames) when opening, or "
                                   "ANIMC_MAX_VERTEX_FRAMES");
  ANIMC_RETURN_IF_ERROR(source.seek(r.first));
  return r;
}

Status checkLayerCount(const std::string& path, const FrameRange& range, int64_t layers) {
  if (layers == range.count()) return Status();
  return invalidArgument("MeshLab made " + std::to_string(layers) + " layers for " + std::to_string(range.count()) +
                         " frames of " + path);
}

}  // namespace animc::meshlab
