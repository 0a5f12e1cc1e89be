// SPDX-License-Identifier: Apache-2.0
// The interface every codec offers the container: frames in, one self-delimited payload per
// frame out, and the reverse. A group starts with an intra frame that needs no earlier one.
// A codec codes frame by frame (FrameEncoder) or a whole group at once (GroupEncoder); the
// decoders of both take one payload per frame.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "codecs/codec_ids.h"
#include "core/sequence.h"
#include "core/status.h"
#include "io/byte_reader.h"

namespace animc {

// Per-frame figures the encoder can report (for logs and benchmarks).
struct FrameCodingStats {
  bool intra = false;
  uint64_t cells = 0;           // leaves of the octree (affine or residual cells)
};

class FrameEncoder {
 public:
  virtual ~FrameEncoder() = default;
  // Appends the payload of xyz (3 * vertex_count floats) to out. intra = true starts a new
  // group; the encoder may also decide to start one (see stats.intra).
  virtual void encodeFrame(const float* xyz, bool intra, std::vector<uint8_t>& out,
                           FrameCodingStats& stats) = 0;
  // The frame the decoder will produce for the last encoded payload.
  virtual const std::vector<double>& reconstruction() const = 0;
};

// A codec that codes the frames of a group together (the trajectory codec): the caller
// gathers up to maxGroupFrames() frames and hands them over at once.
class GroupEncoder {
 public:
  virtual ~GroupEncoder() = default;
  // Most frames one group may hold (its memory grows with vertices x frames).
  virtual uint32_t maxGroupFrames() const = 0;
  // Codes frame_count frames (3 * vertex_count floats each, one after the other) as a
  // group: one payload per frame, the first an intra frame.
  virtual void encodeGroup(const float* frames, uint32_t frame_count, std::vector<std::vector<uint8_t>>& payloads) = 0;
  // Frame k of the last coded group as the decoder will produce it (3 * vertex_count floats);
  // false if the codec's own decoder refuses the group's payloads, which is a bug, reported
  // as such rather than a crash.
  [[nodiscard]] virtual bool reconstruction(uint32_t k, float* xyz) const = 0;
  // What frame k of the last coded group is (whether it is intra, its cells).
  virtual FrameCodingStats frameStats(uint32_t k) const {
    FrameCodingStats stats;
    stats.intra = k == 0;
    return stats;
  }
};

class FrameDecoder {
 public:
  virtual ~FrameDecoder() = default;
  // Decodes one payload into xyz (resized to 3 * vertex_count). Returns whether it was an
  // intra frame through *intra when not null.
  virtual Status decodeFrame(ByteReader payload, std::vector<float>& xyz, bool* intra) = 0;
  // Reads one payload whose frame the caller will not look at: a random access on its way to
  // a later frame of the group. Codecs whose frames build on the ones before decode it as
  // decodeFrame() does; a codec that computes every frame from its group alone may only check
  // the payload and leave xyz as it was.
  virtual Status skipFrame(ByteReader payload, std::vector<float>& xyz, bool* intra) {
    return decodeFrame(payload, xyz, intra);
  }
};

}  // namespace animc
