// SPDX-License-Identifier: Apache-2.0
// The options of every codec, as one type: EncodeSettings holds the chosen codec's options
// only, and the alternative held names the codec (codec_registry.h maps it to its entry).
#pragma once
#include <variant>

#include "codecs/affine_octree/options.h"
#include "codecs/auto/options.h"
#include "codecs/trajectory/options.h"
#include "codecs/wavelet/options.h"

namespace animc {

// One alternative per codec, in Codec_Id order (a new codec appends its options type).
using CodecOptions =
    std::variant<AffineOctreeOptions, WaveletOptions, TrajectoryOptions, AutoOptions, Trajectory2Options>;

}  // namespace animc
