// SPDX-License-Identifier: Apache-2.0
#include "seqio/obj_format.h"

#include <cstring>
#include <limits>
#include <new>
#include <string_view>
#include <vector>

#include "core/atomic_file.h"
#include "seqio/mesh_checks.h"
#include "seqio/text_scan.h"

namespace animc {
namespace {

// The statements of an OBJ file, one line at a time: its keyword, then a cursor over the
// rest. Comments are cut off and lines without a statement skipped.
class ObjLines {
 public:
  ObjLines(const uint8_t* data, size_t size) : pos_(reinterpret_cast<const char*>(data)), end_(pos_ + size) {}

  bool next() {
    while (pos_ < end_) {
      const char* eol = static_cast<const char*>(std::memchr(pos_, '\n', size_t(end_ - pos_)));
      if (!eol) eol = end_;
      const char* comment = static_cast<const char*>(std::memchr(pos_, '#', size_t(eol - pos_)));
      tokens_ = TokenCursor(pos_, comment ? comment : eol);
      pos_ = eol < end_ ? eol + 1 : end_;
      ++line_number_;
      if (tokens_.next(&keyword_)) return true;
    }
    return false;
  }
  std::string_view keyword() const { return keyword_; }
  TokenCursor& tokens() { return tokens_; }
  size_t lineNumber() const { return line_number_; }

 private:
  const char* pos_;
  const char* end_;
  TokenCursor tokens_{nullptr, nullptr};
  std::string_view keyword_;
  size_t line_number_ = 0;
};

Status lineError(const ObjLines& lines, const std::string& what) {
  return corrupt("line " + std::to_string(lines.lineNumber()) + ": " + what);
}

// How many of each list the lines so far have defined: what a corner may refer to.
struct DefinedSoFar {
  uint64_t positions = 0, texture_coordinates = 0, normals = 0;
};

// A corner's reference into a list with `count` elements so far: 1-based, or -1 for the last.
Status resolveIndex(const ObjLines& lines, std::string_view text, uint64_t count, const char* list, uint64_t* index) {
  int64_t value;
  if (!parseInt64(text, &value) || value == 0)
    return lineError(lines, "bad " + std::string(list) + " index '" + std::string(text.substr(0, 40)) + "' in a face");
  if (value > 0 ? uint64_t(value) > count : value < -int64_t(count))
    return lineError(lines, std::string(list) + " index " + std::to_string(value) + " out of range (" +
                                std::to_string(count) + " defined so far)");
  *index = value > 0 ? uint64_t(value) - 1 : count - uint64_t(-value);
  return Status();
}

// "v", "v/vt", "v//vn" or "v/vt/vn": the position's 0-based index; the others are checked.
Status readCorner(const ObjLines& lines, std::string_view corner, const DefinedSoFar& defined, uint32_t* position) {
  const size_t slash = corner.find('/');
  uint64_t index;
  ANIMC_RETURN_IF_ERROR(resolveIndex(lines, corner.substr(0, slash), defined.positions, "vertex", &index));
  *position = uint32_t(index);
  if (slash == std::string_view::npos) return Status();
  const std::string_view rest = corner.substr(slash + 1);
  const size_t second = rest.find('/');
  const std::string_view texture = rest.substr(0, second);
  if (second == std::string_view::npos || !texture.empty())
    ANIMC_RETURN_IF_ERROR(resolveIndex(lines, texture, defined.texture_coordinates, "texture coordinate", &index));
  if (second != std::string_view::npos)
    ANIMC_RETURN_IF_ERROR(resolveIndex(lines, rest.substr(second + 1), defined.normals, "normal", &index));
  return Status();
}

Status readPosition(ObjLines& lines, Mesh* mesh, uint64_t vertex) {
  std::string_view token;
  for (int axis = 0; axis < 3; ++axis) {
    double value;
    if (!lines.tokens().next(&token))
      return lineError(lines, "vertex " + std::to_string(vertex) + " has fewer than 3 coordinates");
    if (!parseDouble(token, &value)) return lineError(lines, "bad number '" + std::string(token.substr(0, 40)) + "'");
    Status finite = checkCoordinate(value, vertex);
    if (!finite.ok()) return finite.withContext("line " + std::to_string(lines.lineNumber()));
    mesh->positions.push_back(float(value));
  }
  return Status();
}

Status readFace(ObjLines& lines, const DefinedSoFar& defined, std::vector<uint32_t>& corners, Mesh* mesh) {
  corners.clear();
  std::string_view token;
  while (lines.tokens().next(&token)) {
    uint32_t position;
    ANIMC_RETURN_IF_ERROR(readCorner(lines, token, defined, &position));
    corners.push_back(position);
  }
  if (corners.size() < 3)
    return lineError(lines, "a face of " + std::to_string(corners.size()) + " vertices (at least 3 needed)");
  for (size_t i = 1; i + 1 < corners.size(); ++i)  // a fan keeps the orientation
    mesh->topology.triangles.push_back({corners[0], corners[i], corners[i + 1]});
  return Status();
}

Status readStatements(ObjLines& lines, Mesh* mesh) {
  DefinedSoFar defined;
  std::vector<uint32_t> corners;
  while (lines.next()) {
    const std::string_view keyword = lines.keyword();
    if (keyword == "v") {
      if (defined.positions == std::numeric_limits<uint32_t>::max())
        return limitExceeded("more vertices than supported (2^32 - 1)");
      ANIMC_RETURN_IF_ERROR(readPosition(lines, mesh, defined.positions));
      ++defined.positions;
    } else if (keyword == "f") {
      ANIMC_RETURN_IF_ERROR(readFace(lines, defined, corners, mesh));
    } else if (keyword == "vt") {
      ++defined.texture_coordinates;
    } else if (keyword == "vn") {
      ++defined.normals;
    }
  }
  mesh->topology.vertex_count = uint32_t(defined.positions);
  return Status();
}

}  // namespace

Result<Mesh> parseObj(const uint8_t* data, size_t size) {
  ObjLines lines(data, size);
  Mesh mesh;
  try {
    ANIMC_RETURN_IF_ERROR(readStatements(lines, &mesh));
  } catch (const std::bad_alloc&) {
    return limitExceeded("out of memory reading an OBJ mesh at line " + std::to_string(lines.lineNumber()));
  }
  ANIMC_RETURN_IF_ERROR(checkTopology(mesh.topology));
  return mesh;
}

std::string objTriangleOrigin(const uint8_t* data, size_t size, size_t t) {
  ObjLines lines(data, size);
  size_t triangles = 0;
  while (lines.next()) {
    if (lines.keyword() != "f") continue;
    size_t corners = 0;
    std::string_view token;
    while (lines.tokens().next(&token)) ++corners;
    if (corners < 3) continue;  // not in a file parseObj accepted
    triangles += corners - 2;
    if (t < triangles) return "the face on line " + std::to_string(lines.lineNumber());
  }
  return "triangle " + std::to_string(t);
}

Status writeObjFile(const std::string& path, const Topology& topology, const float* xyz) {
  std::string text;
  try {
    text.reserve(64 + size_t(topology.vertex_count) * 40 + topology.triangles.size() * 26);
    text += "# written by animcompress\n";
    for (size_t v = 0; v < topology.vertex_count; ++v) {
      text += 'v';
      for (int axis = 0; axis < 3; ++axis) {
        text += ' ';
        appendFloat(text, xyz[3 * v + axis]);
      }
      text += '\n';
    }
    for (const Triangle& triangle : topology.triangles) {
      text += 'f';
      for (uint32_t index : triangle) {
        text += ' ';
        appendUnsigned(text, uint64_t(index) + 1);
      }
      text += '\n';
    }
  } catch (const std::bad_alloc&) {
    return limitExceeded(path + ": out of memory encoding the OBJ frame");
  }
  return writeFileAtomically(path, text.data(), text.size());
}

}  // namespace animc
