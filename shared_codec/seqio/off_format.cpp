// SPDX-License-Identifier: Apache-2.0
#include "seqio/off_format.h"

#include <algorithm>
#include <limits>
#include <new>
#include <string_view>
#include <vector>

#include "core/atomic_file.h"
#include "seqio/mesh_checks.h"
#include "seqio/text_scan.h"

namespace animc {
namespace {

// Yields the tokens of each non-blank line with '#' comments removed.
class OffLines {
 public:
  OffLines(const uint8_t* data, size_t size) : text_(reinterpret_cast<const char*>(data), size) {}

  bool next(std::vector<std::string_view>* tokens) {
    tokens->clear();
    while (tokens->empty() && pos_ < text_.size()) {
      size_t eol = std::min(text_.find('\n', pos_), text_.size());
      std::string_view line = text_.substr(pos_, eol - pos_);
      line = line.substr(0, line.find('#'));
      pos_ = eol + 1;
      ++line_number_;
      TokenCursor cursor(line.data(), line.data() + line.size());
      std::string_view token;
      while (cursor.next(&token)) tokens->push_back(token);
    }
    return !tokens->empty();
  }
  size_t lineNumber() const { return line_number_; }
  size_t remainingBytes() const { return pos_ < text_.size() ? text_.size() - pos_ : 0; }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  size_t line_number_ = 0;
};

Status lineError(const OffLines& lines, const std::string& what) {
  return corrupt("line " + std::to_string(lines.lineNumber()) + ": " + what);
}

struct OffCounts {
  uint64_t vertices = 0;
  uint64_t faces = 0;
};

Result<OffCounts> readCounts(OffLines& lines) {
  std::vector<std::string_view> tokens;
  if (!lines.next(&tokens) ||
      (tokens[0] != "OFF" && tokens[0] != "COFF" && tokens[0] != "NOFF" && tokens[0] != "CNOFF"))
    return corrupt("not an OFF file (no OFF header)");
  if (tokens.size() > 1 && tokens[1] == "BINARY") return corrupt("binary OFF is not supported");
  if (tokens.size() == 1 && !lines.next(&tokens))
    return truncated("OFF file ends before its counts");
  if (tokens.size() > 1 && tokens[0].find("OFF") != std::string_view::npos)
    tokens.erase(tokens.begin());
  OffCounts counts;
  if (tokens.size() < 2 || !parseUint64(tokens[0], &counts.vertices) ||
      !parseUint64(tokens[1], &counts.faces))
    return lineError(lines, "expected 'vertex_count face_count edge_count'");
  // Each vertex line needs at least "0 0 0\n", each face "3 0 1 2\n"; the last newline may lack.
  uint64_t budget = lines.remainingBytes() + 1;
  if (counts.vertices > budget / 6 || counts.faces > (budget - counts.vertices * 6) / 8)
    return truncated("header announces " + std::to_string(counts.vertices) + " vertices and " +
                     std::to_string(counts.faces) + " faces but only " +
                     std::to_string(lines.remainingBytes()) + " bytes follow");
  return counts;
}

Status readVertices(OffLines& lines, Mesh* mesh) {
  std::vector<std::string_view> tokens;
  float* xyz = mesh->positions.data();
  for (uint64_t v = 0; v < mesh->topology.vertex_count; ++v) {
    if (!lines.next(&tokens)) return truncated("file ends at vertex " + std::to_string(v));
    if (tokens.size() < 3)
      return lineError(lines, "vertex " + std::to_string(v) + " has fewer than 3 coordinates");
    for (int axis = 0; axis < 3; ++axis) {
      double value;
      if (!parseDouble(tokens[axis], &value))
        return lineError(lines, "bad number '" + std::string(tokens[axis].substr(0, 40)) + "'");
      ANIMC_RETURN_IF_ERROR(checkCoordinate(value, v));
      xyz[3 * v + axis] = float(value);
    }
  }
  return Status();
}

// Parses "n i j k ..." (extra tokens, such as a colour, are ignored) into corners.
Status readFace(OffLines& lines, const std::vector<std::string_view>& tokens, uint64_t face,
                uint32_t vertex_count, std::vector<uint32_t>& corners) {
  uint64_t length;
  int64_t index;
  if (!parseUint64(tokens[0], &length))
    return lineError(lines, "bad vertex count for face " + std::to_string(face));
  if (length < 3)
    return badInput("face " + std::to_string(face) + " has " + std::to_string(length) +
                    " vertices (at least 3 needed)");
  if (tokens.size() - 1 < length)
    return lineError(lines, "face " + std::to_string(face) + " lists too few indices");
  corners.clear();
  for (uint64_t i = 1; i <= length; ++i) {
    if (!parseInt64(tokens[i], &index))
      return lineError(lines, "bad vertex index in face " + std::to_string(face));
    if (index < 0 || index >= int64_t(vertex_count))
      return badInput("face " + std::to_string(face) + ": vertex index " + std::to_string(index) +
                      " out of range (" + std::to_string(vertex_count) + " vertices)");
    corners.push_back(uint32_t(index));
  }
  return Status();
}

Status readFaces(OffLines& lines, uint64_t face_count, Mesh* mesh) {
  std::vector<std::string_view> tokens;
  std::vector<uint32_t> corners;
  mesh->topology.triangles.reserve(face_count);
  for (uint64_t f = 0; f < face_count; ++f) {
    if (!lines.next(&tokens)) return truncated("file ends at face " + std::to_string(f));
    ANIMC_RETURN_IF_ERROR(readFace(lines, tokens, f, mesh->topology.vertex_count, corners));
    for (size_t i = 1; i + 1 < corners.size(); ++i)  // fan keeps the orientation
      mesh->topology.triangles.push_back({corners[0], corners[i], corners[i + 1]});
  }
  return Status();
}

}  // namespace

Result<Mesh> parseOff(const uint8_t* data, size_t size) {
  OffLines lines(data, size);
  ANIMC_ASSIGN_OR_RETURN(OffCounts counts, readCounts(lines));
  if (counts.vertices > std::numeric_limits<uint32_t>::max())
    return limitExceeded(std::to_string(counts.vertices) + " vertices is more than supported");
  Mesh mesh;
  mesh.topology.vertex_count = uint32_t(counts.vertices);
  try {
    mesh.positions.resize(3 * size_t(counts.vertices));
    ANIMC_RETURN_IF_ERROR(readVertices(lines, &mesh));
    ANIMC_RETURN_IF_ERROR(readFaces(lines, counts.faces, &mesh));
  } catch (const std::bad_alloc&) {
    return limitExceeded("out of memory reading a mesh of " + std::to_string(counts.vertices) +
                         " vertices");
  }
  ANIMC_RETURN_IF_ERROR(checkTopology(mesh.topology));
  return mesh;
}

Status writeOffFile(const std::string& path, const Topology& topology, const float* xyz) {
  std::string text;
  try {
    text = "OFF\n" + std::to_string(topology.vertex_count) + " " +
           std::to_string(topology.triangles.size()) + " 0\n";
    for (size_t v = 0; v < topology.vertex_count; ++v) {
      for (int axis = 0; axis < 3; ++axis) {
        appendFloat(text, xyz[3 * v + axis]);
        text += axis < 2 ? ' ' : '\n';
      }
    }
    for (const Triangle& t : topology.triangles)
      text += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " +
              std::to_string(t[2]) + "\n";
  } catch (const std::bad_alloc&) {
    return limitExceeded(path + ": out of memory encoding the OFF frame");
  }
  return writeFileAtomically(path, text.data(), text.size());
}

}  // namespace animc
