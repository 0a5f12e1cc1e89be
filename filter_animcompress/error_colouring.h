// SPDX-License-Identifier: GPL-3.0-or-later
// Reconstruction error shown on layers: per-vertex error as vertex quality, and a colour ramp
// whose scale is fixed across all frames (so a frame that looks redder really is worse).
#pragma once
#include <cstdint>
#include <vector>

#include <common/meshmodel.h>

namespace animc::meshlab {

// |reconstructed - original| of each of vertex_count vertices, as MeshLab stores quality.
// xyz arrays hold 3 * vertex_count floats.
std::vector<Scalarm> vertexErrors(const float* original, const float* reconstructed, uint32_t vertex_count);

// Stores errors (one per live vertex, in order) as the vertex quality of target.
void storeQuality(MeshModel& target, const std::vector<Scalarm>& errors);

// Stores |reconstructed - original| of every vertex as the quality of `target` (one of the
// two, or a layer with their vertex count). xyz arrays hold 3 * vertex_count floats.
void storeVertexError(MeshModel& target, const float* original, const float* reconstructed);

// Colours `layer` from its vertex quality: blue at 0, red at scale_max and beyond.
void colourByQuality(MeshModel& layer, float scale_max);

}  // namespace animc::meshlab
