// SPDX-License-Identifier: Apache-2.0
// The trajectory codec (docs/trajectory.md): each group of frames as the principal
// components of its vertex trajectories, the coefficients predicted over the mesh.
#pragma once
#include <memory>

#include "animc/animc.h"
#include "codecs/frame_codec.h"
#include "codecs/trajectory/options.h"
#include "core/simd_math.h"

namespace animc {

// `path` chooses the decoded frames' kernel (the same floats either way).
std::unique_ptr<GroupEncoder> makeTrajectoryEncoder(const TrajectoryOptions& options, const Topology& topology,
                                                    SimdPath path);
// Codec 5 (trajectory, version 2): the same groups cut into parts with a basis each.
std::unique_ptr<GroupEncoder> makeTrajectory2Encoder(const Trajectory2Options& options, const Topology& topology,
                                                     SimdPath path);
// The decoders refuse a group whose reconstruction would cost more than
// limits.max_multiply_adds, before decoding any of it.
std::unique_ptr<FrameDecoder> makeTrajectoryDecoder(const Topology& topology, const DecoderLimits& limits,
                                                    SimdPath path);
std::unique_ptr<FrameDecoder> makeTrajectory2Decoder(const Topology& topology, const DecoderLimits& limits,
                                                     SimdPath path);

}  // namespace animc
