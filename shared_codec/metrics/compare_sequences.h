// SPDX-License-Identifier: Apache-2.0
// Two sequences walked side by side into the metrics module's figures: `animc compare` and
// `animc bench` (a file against its decode) and MeshLab's Animation Reconstruction Error
// (two runs of layers) all measure through this one loop.
#pragma once
#include "core/sequence.h"
#include "core/status.h"
#include "metrics/sequence_metrics.h"

namespace animc {

// Reads one frame of each per step until both end. Fails (kBadInput) when their vertex counts
// or frame counts differ, and with the sources' own status when a frame cannot be read.
// progress, when given, is called after each frame with the percent of original.frameCount()
// done (when that count is known) and "measuring errors"; false from it ends with kCancelled.
// sted, when given, receives STED over the original's triangles with the default StedOptions.
Result<SequenceMetrics> compareSequences(FrameSource& original, FrameSource& reconstructed,
                                         const ProgressFn& progress = {},
                                         PerFrameErrors per_frame = PerFrameErrors::kKeep,
                                         StedFigures* sted = nullptr);

}  // namespace animc
