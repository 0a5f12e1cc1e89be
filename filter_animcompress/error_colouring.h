// Reconstruction error shown on layers: per-vertex error as vertex quality, and a colour ramp
// whose scale is fixed across all frames (so a frame that looks redder really is worse).
#pragma once
#include <common/meshmodel.h>

namespace animc::meshlab {

// Stores |reconstructed - original| of every vertex as the quality of `target` (one of the
// two, or a layer with their vertex count). xyz arrays hold 3 * vertex_count floats.
void storeVertexError(MeshModel& target, const float* original, const float* reconstructed);

// Colours `layer` from its vertex quality: blue at 0, red at scale_max and beyond.
void colourByQuality(MeshModel& layer, float scale_max);

}  // namespace animc::meshlab
