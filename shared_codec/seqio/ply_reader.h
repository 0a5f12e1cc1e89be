// SPDX-License-Identifier: Apache-2.0
// Reads a PLY mesh (ascii, binary little- and big-endian): x, y, z among any vertex
// properties, faces as a list of any integer types, polygons fan-triangulated.
#pragma once
#include <cstddef>
#include <cstdint>

#include "core/sequence.h"

namespace animc {

// Parses a whole PLY file held in memory. Messages do not name the file (callers prefix it).
Result<Mesh> parsePly(const uint8_t* data, size_t size);

}  // namespace animc
