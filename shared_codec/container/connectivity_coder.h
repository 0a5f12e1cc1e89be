// SPDX-License-Identifier: Apache-2.0
// The CONN section: the triangle list in its original order (MeshLab layers and the user's
// files must get back exactly their faces). Each index is coded as one of the previous
// triangle's corners, the next never-seen vertex, or a delta from the previous index.
#pragma once
#include <cstdint>
#include <vector>

#include "core/sequence.h"
#include "core/status.h"
#include "io/byte_reader.h"

namespace animc {

void encodeConnectivity(const Topology& topology, std::vector<uint8_t>& out);
// vertex_count and triangle_count come from HEAD (already checked against the limits).
Status decodeConnectivity(ByteReader in, uint32_t vertex_count, uint64_t triangle_count,
                          Topology& topology);

}  // namespace animc
