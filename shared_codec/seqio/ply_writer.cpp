// SPDX-License-Identifier: Apache-2.0
#include "seqio/ply_writer.h"

#include <new>
#include <vector>

#include "core/atomic_file.h"
#include "seqio/endian.h"

namespace animc {
namespace {

std::string plyHeader(const Topology& topology) {
  return "ply\nformat binary_little_endian 1.0\ncomment written by animcompress\n"
         "element vertex " +
         std::to_string(topology.vertex_count) +
         "\nproperty float x\nproperty float y\nproperty float z\n"
         "element face " +
         std::to_string(topology.triangles.size()) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

// The body is built in memory (O(vertices)) so the file gets a single large write.
void encodeBody(const Topology& topology, const float* xyz, std::vector<uint8_t>& body) {
  body.resize(size_t(topology.vertex_count) * 12 + topology.triangles.size() * 13);
  uint8_t* out = body.data();
  for (size_t i = 0; i < size_t(topology.vertex_count) * 3; ++i, out += 4)
    storeLe32(out, floatToBits(xyz[i]));
  for (const Triangle& triangle : topology.triangles) {
    *out++ = 3;
    for (uint32_t index : triangle) {
      storeLe32(out, index);
      out += 4;
    }
  }
}

}  // namespace

Status writePlyFile(const std::string& path, const Topology& topology, const float* xyz) {
  std::vector<uint8_t> body;
  try {
    encodeBody(topology, xyz, body);
  } catch (const std::bad_alloc&) {
    return limitExceeded(path + ": out of memory encoding the PLY frame");
  }
  std::string header = plyHeader(topology);
  AtomicFile file;
  ANIMC_RETURN_IF_ERROR(file.open(path));
  ANIMC_RETURN_IF_ERROR(file.write(header.data(), header.size()));
  ANIMC_RETURN_IF_ERROR(file.write(body.data(), body.size()));
  return file.commit();
}

}  // namespace animc
