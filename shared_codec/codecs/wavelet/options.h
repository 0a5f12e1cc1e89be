// SPDX-License-Identifier: Apache-2.0
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
  // P-frames coded without temporal contexts (the last frame's bitplane history), so that a
  // decoder may cut them (progressive decoding): a cut P-frame then leaves the decoder's
  // reference off the encoder's, and that error carries through the later P-frames of the
  // group (drift) until the next parametric frame. Costs a few percent more bits
  // (docs/benchmarks.md).
  bool progressive_p_frames = false;
  // Details in the local frame of their coarser ring (the paper) rather than world axes.
  // Off by default: the frames' rotation by quantisation errors of the coarser levels
  // multiplies the error at the same step (docs/wavelet.md).
  bool local_frames = false;
  // Rate control by target error, in percent of the KG error (0 = off): each detail frame is
  // cut after the shortest prefix of its bitplanes whose float output has a squared error
  // <= (target_kg / 100)^2 * sum |x - centroid|^2 of that frame, and parametric frames get
  // a finer grid than parametric_bits when they need it; summed over frames, the sequence's
  // KG error is then <= target_kg. `step` still sets the finest plane available (a target
  // the step cannot reach is missed), and a bits_per_vertex budget wins over the target.
  // Encoder only; stored so that `animc info` can show it.
  double target_kg = 0;
  // Write the per-bitplane byte checkpoints that let a payload cut at any byte decode to its
  // last complete bitplane (about 1.5 bytes per bitplane per frame).
  bool truncatable = true;

  // Whether a decoder may cut this stream's detail frames (WaveletDecodeControl).
  bool cuttable() const { return !temporal_prediction || progressive_p_frames; }

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
constexpr double kMaxTargetKg = 100;

// What a decoder may be asked to drop (progressive decoding); not part of the stream.
using WaveletDecodeControl = ProgressiveOptions;

}  // namespace animc
