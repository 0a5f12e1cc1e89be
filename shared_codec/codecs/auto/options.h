// SPDX-License-Identifier: Apache-2.0
// Settings of `--codec auto` (docs/auto.md): the error every group must meet, and the codecs
// that compete for each group with their parameters, which the decoder needs.
#pragma once
#include <cstdint>
#include <vector>

#include "codecs/codec_ids.h"
#include "codecs/trajectory/options.h"
#include "core/status.h"
#include "io/byte_reader.h"
#include "io/byte_writer.h"

namespace animc {

// One competing codec: its Codec_Id and its Codec_Params, as its own streams carry them.
struct AutoCandidate {
  CodecId codec;
  std::vector<uint8_t> params;
};

struct AutoOptions {
  // kTargetKg (percent) or kMaxError (fraction of the frame's cube side); the others are
  // refused. The default is the affine-octree codec's default bound.
  TrajectoryRate rate = TrajectoryRate::kMaxError;
  double rate_value = 0.01;
  uint32_t group_frames = 512;  // as the trajectory codec's
  // Filled by withCandidates() from the above on the encoder side; read from the file on the
  // decoder side.
  std::vector<AutoCandidate> candidates;

  Status validate() const;
  void write(ByteWriter& w) const;
  static Result<AutoOptions> read(ByteReader& r);
};

// The options with the candidates for their rate: the trajectory codec's version 2 (codec 5,
// its default parts) and, for a KG target,
// the wavelet codec with the same target, or, for a max error, the affine-octree codec
// (default profile) with the same bound.
AutoOptions withCandidates(AutoOptions options);

constexpr uint8_t kMaxAutoCandidates = 8;

}  // namespace animc
