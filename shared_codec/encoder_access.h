// SPDX-License-Identifier: Apache-2.0
// What the library's own code reaches inside an Encoder, beyond its public API.
#pragma once
#include <memory>

#include "api.h"

namespace animc {

struct EncoderAccess {
  static Result<Encoder> create(const EncodeSettings& settings, Topology topology, double frame_rate,
                                std::unique_ptr<ByteSink> sink);
  // Frame k as it was added, for a frame whose reconstruction() is known, until the next
  // addFrame(): the encoder's own copy of a coded group, or the caller's array of the last
  // frame added by a frame-by-frame codec. Null for any other frame.
  static const float* original(const Encoder& encoder, int64_t frame);
};

}  // namespace animc
