// SPDX-License-Identifier: Apache-2.0
// Writes one frame as a binary little-endian PLY: float x y z, uchar-count int faces.
#pragma once
#include <string>

#include "core/sequence.h"

namespace animc {

// Writes atomically (temp file + rename); xyz holds 3 * topology.vertex_count floats.
Status writePlyFile(const std::string& path, const Topology& topology, const float* xyz);

}  // namespace animc
