// SPDX-License-Identifier: Apache-2.0
// A group of codec 5 (trajectory, version 2; docs/format.md, section 16): the mesh's vertices
// in parts, each part labelled along the mesh and coded as a codec-3 group of its own
// sub-mesh. This file holds what its encoder and its decoder share: the parts of a labelling,
// their sub-meshes, and the group's payload.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "codecs/trajectory/group_coding.h"
#include "codecs/trajectory/options.h"
#include "core/sequence.h"
#include "core/status.h"
#include "io/byte_reader.h"

namespace animc {

// The parts of a labelling (labels[v] < count, every part holding a vertex): each part's
// vertices in increasing order, its sub-mesh (the triangles whose three vertices are in it,
// renumbered) and that sub-mesh's coding order.
struct MeshParts {
  MeshParts(const Topology& mesh, const std::vector<uint8_t>& labels, uint32_t count);
  std::vector<std::vector<uint32_t>> members;
  std::vector<std::unique_ptr<const CodingOrder>> orders;
};

// Writes a whole group payload, Frame_Type first: `mesh_order` is the whole mesh's coding
// order (the labels follow it), parts[c] is coded with parts.orders[c].
void writePartedGroup(uint32_t frames, const std::vector<uint8_t>& labels, const CodingOrder& mesh_order,
                      const MeshParts& parts, const std::vector<TrajectoryGroup>& groups, std::vector<uint8_t>& out);

// A group payload after its Frame_Type, read into labels and, for each part, its payload
// (the codec-3 group of section 12.3) and the work of its reconstruction, all checked but the
// parts' coded data: Part_Count, the labels, each part's Frame_Count and Component_Count.
struct PartedGroupHead {
  uint32_t frames = 0;
  uint32_t part_count = 0;
  std::vector<uint8_t> labels;
  std::vector<ByteReader> parts;
  uint64_t multiply_adds = 0;  // of the whole group's reconstruction
};
Status readPartedGroupHead(ByteReader payload, const CodingOrder& mesh_order, PartedGroupHead& head);

}  // namespace animc
