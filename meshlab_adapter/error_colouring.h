// SPDX-License-Identifier: GPL-3.0-or-later
// Reconstruction error shown on layers: per-vertex error as vertex quality, and a colour ramp
// whose scale is fixed across all frames (so a frame that looks redder really is worse).
#pragma once
#include <cstdint>
#include <vector>

#include "meshlab_compat.h"

namespace animc::meshlab {

// Stores errors (one per live vertex, in order) as the vertex quality of target. The errors
// come from the metrics library's per-vertex callback (MetricsAccumulator::addFrame), the one
// definition of a vertex's error.
void storeQuality(MeshModel& target, const std::vector<Scalarm>& errors);

// Colours `layer` from its vertex quality: blue at 0, red at scale_max and beyond.
void colourByQuality(MeshModel& layer, float scale_max);

}  // namespace animc::meshlab
