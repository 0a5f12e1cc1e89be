// SPDX-License-Identifier: Apache-2.0
// The interface every codec offers the container: frames in, one self-delimited payload per
// frame out, and the reverse. A group starts with an intra frame that needs no earlier one.
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

class FrameDecoder {
 public:
  virtual ~FrameDecoder() = default;
  // Decodes one payload into xyz (resized to 3 * vertex_count). Returns whether it was an
  // intra frame through *intra when not null.
  virtual Status decodeFrame(ByteReader payload, std::vector<float>& xyz, bool* intra) = 0;
};

}  // namespace animc
