// SPDX-License-Identifier: Apache-2.0
// The CONN section: the triangle list in its original order (MeshLab layers and the user's
// files must get back exactly their faces). Each index is coded as one of the previous
// triangle's corners, the next never-seen vertex, or a delta from the previous index.
//
// Format 1 codes the list as one stream, which a decoder can only read on one thread. Format 2
// cuts it into pieces of a fixed number of triangles, each coded afresh, so that the pieces
// decode at once (docs/format.md, section 6.2).
#pragma once
#include <cstdint>
#include <vector>

#include "core/sequence.h"
#include "core/status.h"
#include "io/byte_reader.h"

namespace animc {

// The format version a file needs for its CONN: 2 when the triangles are cut into more than
// one piece of piece_triangles (0: never cut), else 1.
uint16_t formatVersionFor(uint64_t triangle_count, uint32_t piece_triangles);

// Appends CONN's payload for formatVersionFor(topology's triangles, piece_triangles). The
// pieces of a format-2 payload are coded on the calling thread's budget (ThreadBudget).
void encodeConnectivity(const Topology& topology, uint32_t piece_triangles, std::vector<uint8_t>& out);
// vertex_count and triangle_count come from HEAD (already checked against the limits). The
// pieces of a format-2 payload decode on the calling thread's budget (ThreadBudget).
Status decodeConnectivity(ByteReader in, uint16_t format_version, uint32_t vertex_count, uint64_t triangle_count,
                          Topology& topology);

}  // namespace animc
