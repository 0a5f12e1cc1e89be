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

// The `count` parts of `labels` grouped into at most `parts` by k-means of the parts' centres
// (the means of their vertices' features), each weighted by its vertices: a coarser cut whose
// parts are unions of the finer's. Numbered as clusterTrajectories() numbers them; `merged`
// is set to their number.
std::vector<uint8_t> mergeParts(const float* frames, uint32_t vertices, uint32_t frame_count,
                                const std::vector<uint8_t>& labels, uint32_t count, uint32_t parts, uint32_t& merged);

}  // namespace animc
