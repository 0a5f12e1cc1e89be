// SPDX-License-Identifier: Apache-2.0
// The parts of a codec-5 group: vertices whose trajectories move together, found by k-means
// (docs/trajectory.md, "Parts"). A part then needs few components of its own where the whole
// mesh needs the components of every part.
#pragma once
#include <cstdint>
#include <vector>

namespace animc {

// A part index per vertex, for at most `parts` parts, numbered 0 ... count - 1 in the order
// of their lowest vertex (none empty); `count` is set to the number of parts. frames holds
// frame_count frames of 3 floats a vertex. The result does not depend on the thread count.
std::vector<uint8_t> clusterTrajectories(const float* frames, uint32_t vertices, uint32_t frame_count, uint32_t parts,
                                         uint32_t& count);

}  // namespace animc
