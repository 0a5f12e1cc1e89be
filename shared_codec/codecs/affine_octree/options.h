// SPDX-License-Identifier: Apache-2.0
// Encoder settings of the Affine-Octree codec; they travel in the container's HEAD section so
// the decoder rebuilds exactly the encoder's state.
#pragma once
#include <cstdint>

#include "codecs/codec_ids.h"
#include "core/status.h"
#include "io/byte_reader.h"
#include "io/byte_writer.h"

namespace animc {

struct AffineOctreeOptions {
  Profile profile = Profile::kPredictive;
  // Largest allowed vertex error, as a fraction of the side of the root cube (the bounding
  // cube of the reference frame). 0.01 is the paper's "ME = 1%".
  double max_error = 0.01;
  // Paper profile: bits per affine element and per stored coordinate (the paper uses 16).
  int bits = 16;
  // Deepest octree level; a cell there that still misses max_error stores its positions.
  int max_depth = 10;

  Status validate() const;
  void write(ByteWriter& w) const;
  static Result<AffineOctreeOptions> read(ByteReader& r);
};

// "paper", "predictive".
const char* profileName(Profile p);

// Ranges accepted by validate() and by the decoder.
constexpr double kMinMaxError = 1e-6;
constexpr double kMaxMaxError = 0.5;
constexpr int kMinBits = 8;
constexpr int kMaxBits = 24;
constexpr int kMaxDepthLimit = 16;

}  // namespace animc
