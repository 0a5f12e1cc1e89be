// SPDX-License-Identifier: Apache-2.0
// A frame-by-frame codec as a GroupEncoder, for callers that code whole groups (auto's
// candidates, the Encoder's groups coded on several threads): each group is coded by a fresh
// encoder, as its decoder starts afresh at the group's intra frame, and the frames the decoder
// will make of it are kept.
#pragma once
#include <memory>

#include "codecs/codec_registry.h"

namespace animc {

std::unique_ptr<GroupEncoder> makeFrameGroupEncoder(const CodecEntry& codec, const CodecOptions& options,
                                                    const Topology& topology, SimdPath path);

// The codec's own GroupEncoder, or the frame-by-frame one above.
std::unique_ptr<GroupEncoder> makeAnyGroupEncoder(const CodecEntry& codec, const CodecOptions& options,
                                                  const Topology& topology, SimdPath path);

}  // namespace animc
