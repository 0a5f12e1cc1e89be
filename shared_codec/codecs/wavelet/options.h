// Encoder settings of the wavelet codec (Guskov & Khodakovsky 2004, docs/wavelet.md). They
// travel in the container's codec parameters so the decoder rebuilds the encoder's state.
#pragma once
#include <cstdint>

#include "core/status.h"
#include "io/byte_reader.h"
#include "io/byte_writer.h"

namespace animc {

struct WaveletOptions {
  // Fixed rate: payload bytes of each detail frame <= bits_per_vertex * N / 8 (the bitplane
  // stream is cut there). 0 = no budget: every bitplane down to `step` is sent.
  double bits_per_vertex = 0;
  // Finest quantisation step of the (area-weighted) wavelet coefficients, as a fraction of the
  // bounding-box diagonal of the parametric mesh. It bounds the quality when there is no budget.
  double step = 1e-4;
  // Grid of the parametric (static) frame: 2^parametric_bits steps over the largest side of
  // its bounding box. The paper wants it at least as precise as the detail frames.
  int parametric_bits = 14;
  // false: every detail frame is an I-frame (the paper's "I-frames only" figures).
  bool temporal_prediction = true;
  // Details in the local frame of their coarser ring (the paper) rather than world axes.
  // Off by default: on chickenCrossing the frames' rotation by quantisation errors of the
  // coarser levels multiplies the error 15-25x at the same step (docs/wavelet.md).
  bool local_frames = false;
  // Write the per-bitplane byte checkpoints that let a payload cut at any byte decode to its
  // last complete bitplane (about 1.5 bytes per bitplane per frame).
  bool truncatable = true;

  Status validate() const;
  void write(ByteWriter& w) const;
  static Result<WaveletOptions> read(ByteReader& r);
};

// Ranges accepted by validate() and by the decoder.
constexpr double kMaxBitsPerVertex = 1024;
constexpr double kMinWaveletStep = 1e-9;
constexpr double kMaxWaveletStep = 1.0;
constexpr int kMinParametricBits = 4;
constexpr int kMaxParametricBits = 28;

// What a decoder may be asked to drop (progressive decoding); not part of the stream.
struct WaveletDecodeControl {
  int max_bitplanes = 0;          // decode at most this many bitplanes per frame; 0 = all
  uint64_t max_payload_bytes = 0;  // read at most this many bytes of each frame; 0 = all
};

}  // namespace animc
