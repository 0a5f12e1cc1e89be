// SPDX-License-Identifier: Apache-2.0
// OFF meshes: "OFF", then "vertices faces edges", vertex lines "x y z", face lines
// "n i j k ..." (polygons fan-triangulated); '#' starts a comment. ASCII only.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/sequence.h"

namespace animc {

// Parses a whole OFF file held in memory. Messages name the line but not the file.
Result<Mesh> parseOff(const uint8_t* data, size_t size);

// Writes atomically, coordinates with 9 significant digits (exact float round trip).
Status writeOffFile(const std::string& path, const Topology& topology, const float* xyz);

}  // namespace animc
