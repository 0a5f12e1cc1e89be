// SPDX-License-Identifier: Apache-2.0
#include "seqio/ply_reader.h"

#include <limits>
#include <new>
#include <string>

#include "seqio/mesh_checks.h"
#include "seqio/ply_header.h"
#include "seqio/ply_values.h"

namespace animc {
namespace {

const PlyElement* findElement(const PlyHeader& header, const char* name) {
  for (const PlyElement& element : header.elements)
    if (element.name == name) return &element;
  return nullptr;
}

// A list length: a non-negative integer (signed count types could say -1).
bool readListLength(PlyValueReader& in, const PlyProperty& p, uint64_t* length, Status* error) {
  double value;
  if (!in.read(p.count_type, &value)) return *error = in.status(), false;
  if (value < 0) return *error = corrupt("negative list length in property " + p.name), false;
  *length = uint64_t(value);
  return true;
}

Status skipProperty(PlyValueReader& in, const PlyProperty& p) {
  double value;
  uint64_t length = 1;
  Status error;
  if (p.is_list && !readListLength(in, p, &length, &error)) return error;
  for (uint64_t i = 0; i < length; ++i)
    if (!in.read(p.type, &value)) return in.status();
  return Status();
}

Status skipElement(PlyValueReader& in, const PlyElement& element) {
  // Without properties an instance takes no bytes, so checkPlyDataSize() lets any count
  // through: skip them all at once rather than loop up to 2^64 times over nothing.
  if (element.properties.empty()) return Status();
  for (uint64_t i = 0; i < element.count; ++i)
    for (const PlyProperty& p : element.properties) ANIMC_RETURN_IF_ERROR(skipProperty(in, p));
  return Status();
}

// Property index -> 0, 1, 2 for x, y, z; -1 for the properties to skip.
std::vector<int> axisOfProperties(const PlyElement& element) {
  std::vector<int> axis_of;
  for (const PlyProperty& p : element.properties) {
    int axis = p.is_list ? -1 : p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
    axis_of.push_back(axis);
  }
  return axis_of;
}

// Checked before allocating: it also guarantees each vertex costs bytes in the file.
Status checkVertexProperties(const PlyElement& element) {
  int found = 0;
  for (int axis : axisOfProperties(element))
    if (axis >= 0) found |= 1 << axis;
  if (found != 7) return corrupt("vertex element lacks an x, y or z property");
  return Status();
}

Status readVertices(PlyValueReader& in, const PlyElement& element, Mesh* mesh) {
  std::vector<int> axis_of = axisOfProperties(element);
  float* xyz = mesh->positions.data();
  for (uint64_t v = 0; v < element.count; ++v) {
    for (size_t k = 0; k < element.properties.size(); ++k) {
      if (axis_of[k] < 0) {
        ANIMC_RETURN_IF_ERROR(skipProperty(in, element.properties[k]));
        continue;
      }
      double value;
      if (!in.read(element.properties[k].type, &value)) return in.status();
      ANIMC_RETURN_IF_ERROR(checkCoordinate(value, v));
      xyz[3 * v + axis_of[k]] = float(value);
    }
  }
  return Status();
}

// The face list property: "vertex_indices" (or "vertex_index"), else the only list there is.
int faceListIndex(const PlyElement& element) {
  int any_list = -1;
  for (size_t k = 0; k < element.properties.size(); ++k) {
    const PlyProperty& p = element.properties[k];
    if (!p.is_list) continue;
    if (p.name == "vertex_indices" || p.name == "vertex_index") return int(k);
    if (any_list < 0) any_list = int(k);
  }
  return any_list;
}

Status readFace(PlyValueReader& in, const PlyProperty& p, uint64_t face,
                std::vector<uint32_t>& corners, Mesh* mesh) {
  uint64_t length;
  Status error;
  if (!readListLength(in, p, &length, &error)) return error;
  if (length < 3)
    return badInput("face " + std::to_string(face) + " has " + std::to_string(length) +
                    " vertices (at least 3 needed)");
  corners.clear();
  for (uint64_t i = 0; i < length; ++i) {
    double index;
    if (!in.read(p.type, &index)) return in.status();
    // Integer item types only (checked by readFaces), so the conversions below are exact.
    if (!(index >= 0 && index < double(mesh->topology.vertex_count)))
      return badInput("face " + std::to_string(face) + ": vertex index " +
                      std::to_string(int64_t(index)) + " out of range (" +
                      std::to_string(mesh->topology.vertex_count) + " vertices)");
    corners.push_back(uint32_t(index));
  }
  // Fan triangulation keeps the polygon's orientation.
  for (size_t i = 1; i + 1 < corners.size(); ++i)
    mesh->topology.triangles.push_back({corners[0], corners[i], corners[i + 1]});
  return Status();
}

// Fewest bytes a face can take: any instance of its element (ply_header.h) plus the three
// indices readFace() needs at least.
uint64_t minFaceBytes(const PlyElement& element, const PlyProperty& list, bool ascii) {
  return plyMinInstanceBytes(element, ascii) + 3 * (ascii ? 2 : plyTypeSize(list.type));
}

// A header may declare any face count: one the bytes left cannot hold is a cut (or lying)
// file, said before anything is reserved for the faces.
Status checkFaceCount(const PlyValueReader& in, const PlyElement& element, const PlyProperty& list) {
  const bool ascii = in.format() == PlyFormat::kAscii;
  // The last value needs no separator.
  const uint64_t left = uint64_t(in.remaining()) + (ascii ? 1 : 0);
  const uint64_t at_most = left / minFaceBytes(element, list, ascii);
  if (element.count > at_most)
    return truncated("data ends early (truncated file): the header declares " +
                     std::to_string(element.count) + " faces but the " +
                     std::to_string(in.remaining()) + " bytes left can hold at most " +
                     std::to_string(at_most));
  return Status();
}

Status readFaces(PlyValueReader& in, const PlyElement& element, Mesh* mesh) {
  int list = faceListIndex(element);
  if (list < 0) return corrupt("face element has no vertex_indices list");
  if (!plyTypeIsInteger(element.properties[list].type))
    return corrupt("face vertex indices are not of an integer type");
  ANIMC_RETURN_IF_ERROR(checkFaceCount(in, element, element.properties[list]));
  // One triangle per face, a reservation checkFaceCount() bounded by the bytes left (at most
  // 1.5 bytes of memory per byte of file); polygons' further triangles grow it as they are read.
  mesh->topology.triangles.reserve(element.count);
  std::vector<uint32_t> corners;
  for (uint64_t f = 0; f < element.count; ++f) {
    for (size_t k = 0; k < element.properties.size(); ++k) {
      if (int(k) == list)
        ANIMC_RETURN_IF_ERROR(readFace(in, element.properties[k], f, corners, mesh));
      else
        ANIMC_RETURN_IF_ERROR(skipProperty(in, element.properties[k]));
    }
  }
  return Status();
}

// `vertices` is the element positions were sized for; a second "vertex" element is skipped.
Status readBody(const PlyHeader& header, const PlyElement* vertices, const uint8_t* data,
                size_t size, Mesh* mesh) {
  PlyValueReader in(header.format, data, size, header.data_offset);
  for (const PlyElement& element : header.elements) {
    if (&element == vertices)
      ANIMC_RETURN_IF_ERROR(readVertices(in, element, mesh));
    else if (element.name == "face")
      ANIMC_RETURN_IF_ERROR(readFaces(in, element, mesh));
    else
      ANIMC_RETURN_IF_ERROR(skipElement(in, element));
  }
  return Status();
}

}  // namespace

Result<Mesh> parsePly(const uint8_t* data, size_t size) {
  ANIMC_ASSIGN_OR_RETURN(PlyHeader header, parsePlyHeader(data, size));
  ANIMC_RETURN_IF_ERROR(checkPlyDataSize(header, size - header.data_offset));
  const PlyElement* vertices = findElement(header, "vertex");
  uint64_t vertex_count = vertices ? vertices->count : 0;
  if (vertex_count > std::numeric_limits<uint32_t>::max())
    return limitExceeded(std::to_string(vertex_count) + " vertices is more than supported");
  if (vertices) ANIMC_RETURN_IF_ERROR(checkVertexProperties(*vertices));
  Mesh mesh;
  mesh.topology.vertex_count = uint32_t(vertex_count);
  try {
    mesh.positions.resize(3 * size_t(vertex_count));
    ANIMC_RETURN_IF_ERROR(readBody(header, vertices, data, size, &mesh));
  } catch (const std::bad_alloc&) {
    return limitExceeded("out of memory reading a mesh of " + std::to_string(vertex_count) +
                         " vertices");
  }
  ANIMC_RETURN_IF_ERROR(checkTopology(mesh.topology));
  return mesh;
}

}  // namespace animc
