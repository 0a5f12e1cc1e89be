// SPDX-License-Identifier: Apache-2.0
// The trajectory codec (docs/trajectory.md): each group of frames as the principal
// components of its vertex trajectories, the coefficients predicted over the mesh.
#pragma once
#include <memory>

#include "codecs/frame_codec.h"
#include "codecs/trajectory/options.h"
#include "core/simd_math.h"

namespace animc {

// `path` chooses the decoded frames' kernel (the same floats either way).
std::unique_ptr<GroupEncoder> makeTrajectoryEncoder(const TrajectoryOptions& options, const Topology& topology,
                                                    SimdPath path);
std::unique_ptr<FrameDecoder> makeTrajectoryDecoder(const Topology& topology, SimdPath path);

}  // namespace animc
