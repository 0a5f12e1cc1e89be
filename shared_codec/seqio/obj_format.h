// SPDX-License-Identifier: Apache-2.0
// Wavefront OBJ meshes, as exporters write them: "v x y z" (a fourth number, w, or three more,
// a colour, are ignored), "f" with corners in any of the four forms v, v/vt, v//vn, v/vt/vn
// (1-based, or negative: -1 is the last one defined so far), polygons fan-triangulated from
// their first corner. vt and vn are checked but not kept (a sequence shares one connectivity
// and the codecs code positions only); o, g, s, usemtl, mtllib, l, p and every other
// statement are skipped. '#' starts a comment; CRLF and a last line without a newline are
// fine. Positions are kept in file order, so the vertex order is that of the v lines.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/sequence.h"

namespace animc {

// Parses a whole OBJ file held in memory. Messages name the line but not the file.
Result<Mesh> parseObj(const uint8_t* data, size_t size);

// For a file parseObj accepted: "face 7 (line 12)", the face triangle `t` was cut from.
std::string objTriangleOrigin(const uint8_t* data, size_t size, size_t t);

// Writes atomically: v lines with 9 significant digits (exact float round trip), then one
// "f a b c" per triangle.
Status writeObjFile(const std::string& path, const Topology& topology, const float* xyz);

}  // namespace animc
