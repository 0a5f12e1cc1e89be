// SPDX-License-Identifier: Apache-2.0
// The Affine-Octree codec as seen by the container: intra frames through StaticPositionCoder,
// inter frames through the profile's octree coder, closed loop on the reconstruction.
#pragma once
#include <memory>

#include "codecs/affine_octree/options.h"
#include "codecs/frame_codec.h"
#include "core/simd_math.h"

namespace animc {

// path: the kernels' version (core/simd_math.h), the same bytes and frames either way.
std::unique_ptr<FrameEncoder> makeAffineOctreeEncoder(const AffineOctreeOptions& options,
                                                      const Topology& topology, SimdPath path);
std::unique_ptr<FrameDecoder> makeAffineOctreeDecoder(const AffineOctreeOptions& options,
                                                      const Topology& topology, SimdPath path);

// Grid step of intra frames for a frame whose root cube has the given side.
double intraStep(const AffineOctreeOptions& options, double side);

}  // namespace animc
