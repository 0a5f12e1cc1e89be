// SPDX-License-Identifier: Apache-2.0
// Validation shared by every reader, so a bad input is rejected with the same words whatever
// its format: non-finite or huge coordinates, empty meshes, out-of-range or changing faces.
#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include "core/sequence.h"

namespace animc {

// Checks `vertex_count` xyz triples; the message names the first bad vertex.
Status checkPositions(const float* xyz, uint32_t vertex_count);
// Checks one coordinate before it is narrowed to float (PLY may store doubles).
Status checkCoordinate(double value, uint64_t vertex);
// Non-empty, and every triangle index below vertex_count.
Status checkTopology(const Topology& topology);
// Same vertex count and triangle list; `other_name` says what `expected` came from
// ("frame 0", "the mesh cow.ply"). The message does not name the file being checked; it names
// the first differing triangle t as `origin(t)` ("the face on line 12"), or "triangle t".
Status checkSameTopology(const Topology& actual, const Topology& expected, const std::string& other_name,
                         const std::function<std::string(size_t)>& origin = nullptr);

}  // namespace animc
