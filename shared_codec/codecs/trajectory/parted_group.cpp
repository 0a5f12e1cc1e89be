// SPDX-License-Identifier: Apache-2.0
#include "codecs/trajectory/parted_group.h"

#include <algorithm>

#include "codecs/trajectory/options.h"
#include "entropy/bit_tree.h"
#include "entropy/range_coder.h"
#include "io/byte_writer.h"

namespace animc {
namespace {

constexpr int kLabelBits = 6;
static_assert(kMaxTrajectoryParts == 1u << kLabelBits, "a label is one symbol of the label tree");

// A vertex's label is predicted by that of its earlier neighbour first in the coding order
// (the one that reached it): parts are mostly connected, so most labels repeat it. Whether
// all its earlier neighbours agree picks the model of the repeat flag.
struct LabelModels {
  BitModel repeat[2];              // earlier neighbours disagree, agree
  BitTreeModel<kLabelBits> label;  // a label that is not the prediction's, or has none
};

struct LabelPrediction {
  bool any = false;  // an earlier neighbour
  bool agree = false;
  uint8_t label = 0;
};

LabelPrediction predictLabel(const CodingOrder& order, const std::vector<uint8_t>& labels, uint32_t p) {
  LabelPrediction out;
  uint32_t first = UINT32_MAX;
  for (uint32_t i = order.first[p]; i < order.first[p + 1]; ++i) first = std::min(first, order.earlier[i]);
  if (first == UINT32_MAX) return out;
  out.any = true;
  out.label = labels[order.vertex[first]];
  out.agree = true;
  for (uint32_t i = order.first[p]; i < order.first[p + 1]; ++i)
    out.agree &= labels[order.vertex[order.earlier[i]]] == out.label;
  return out;
}

void writeLabels(const CodingOrder& order, const std::vector<uint8_t>& labels, std::vector<uint8_t>& out) {
  auto models = std::make_unique<LabelModels>();
  RangeEncoder rc(out);
  for (uint32_t p = 0; p < order.vertex.size(); ++p) {
    const uint8_t label = labels[order.vertex[p]];
    const LabelPrediction pred = predictLabel(order, labels, p);
    if (pred.any) {
      rc.encode(models->repeat[pred.agree], label == pred.label);
      if (label == pred.label) continue;
    }
    encodeTree(rc, models->label, label);
  }
  rc.finish();
}

Status readLabels(ByteReader coded, const CodingOrder& order, uint32_t part_count, std::vector<uint8_t>& labels) {
  const uint32_t n = uint32_t(order.vertex.size());
  labels.assign(n, 0);
  auto models = std::make_unique<LabelModels>();
  RangeDecoder rc(coded.cursor(), coded.remaining());
  for (uint32_t p = 0; p < n; ++p) {
    const LabelPrediction pred = predictLabel(order, labels, p);
    uint32_t label = pred.label;
    if (!pred.any || !rc.decode(models->repeat[pred.agree])) label = decodeTree(rc, models->label);
    if (label >= part_count) return corrupt("trajectory group: a vertex's part is past Part_Count");
    labels[order.vertex[p]] = uint8_t(label);
  }
  if (rc.overran()) return corrupt("trajectory group: the parts' labels end early or are damaged");
  return Status();
}

}  // namespace

MeshParts::MeshParts(const Topology& mesh, const std::vector<uint8_t>& labels, uint32_t count) : members(count) {
  std::vector<uint32_t> local(mesh.vertex_count);
  for (uint32_t v = 0; v < mesh.vertex_count; ++v) {
    local[v] = uint32_t(members[labels[v]].size());
    members[labels[v]].push_back(v);
  }
  std::vector<Topology> sub(count);
  for (uint32_t c = 0; c < count; ++c) sub[c].vertex_count = uint32_t(members[c].size());
  for (const Triangle& t : mesh.triangles) {
    const uint8_t c = labels[t[0]];
    if (labels[t[1]] == c && labels[t[2]] == c) sub[c].triangles.push_back({local[t[0]], local[t[1]], local[t[2]]});
  }
  for (uint32_t c = 0; c < count; ++c) orders.push_back(std::make_unique<const CodingOrder>(sub[c]));
}

void writePartedGroup(uint32_t frames, const std::vector<uint8_t>& labels, const CodingOrder& mesh_order,
                      const MeshParts& parts, const std::vector<TrajectoryGroup>& groups, std::vector<uint8_t>& out) {
  ByteWriter head;
  head.u8(kTrajectoryGroupFrame);
  head.u16(uint16_t(frames));
  head.u8(uint8_t(groups.size()));
  out.insert(out.end(), head.bytes().begin(), head.bytes().end());
  // Each block after its u32 length, which the decoder checks before reading any of it.
  auto block = [&](auto write) {
    const size_t at = out.size();
    out.resize(at + 4);
    write();
    const uint32_t length = uint32_t(out.size() - at - 4);
    for (int i = 0; i < 4; ++i) out[at + i] = uint8_t(length >> (8 * i));
  };
  if (groups.size() > 1) block([&] { writeLabels(mesh_order, labels, out); });
  for (size_t c = 0; c < groups.size(); ++c)
    block([&] { writeTrajectoryGroupFields(groups[c], *parts.orders[c], out); });
}

Status readPartedGroupHead(ByteReader payload, const CodingOrder& mesh_order, PartedGroupHead& head) {
  ANIMC_ASSIGN_OR_RETURN(uint16_t frames, payload.u16("Frame_Count"));
  ANIMC_ASSIGN_OR_RETURN(uint8_t part_count, payload.u8("Part_Count"));
  const uint32_t n = uint32_t(mesh_order.vertex.size());
  if (frames < 1 || frames > kMaxTrajectoryGroupFrames)
    return corrupt("trajectory group of " + std::to_string(frames) + " frames, outside [1, " +
                   std::to_string(kMaxTrajectoryGroupFrames) + "]");
  if (part_count < 1 || part_count > std::min(kMaxTrajectoryParts, n))
    return corrupt("trajectory group of " + std::to_string(part_count) + " parts, outside [1, " +
                   std::to_string(std::min(kMaxTrajectoryParts, n)) + "]");
  head.frames = frames;
  head.part_count = part_count;
  if (part_count > 1) {
    ANIMC_ASSIGN_OR_RETURN(uint32_t length, payload.u32("Labels_Length"));
    ANIMC_ASSIGN_OR_RETURN(ByteReader coded, payload.subReader(length, "Labels"));
    ANIMC_RETURN_IF_ERROR(readLabels(coded, mesh_order, part_count, head.labels));
  } else {
    head.labels.assign(n, 0);
  }
  std::vector<uint64_t> sizes(part_count, 0);
  for (uint8_t label : head.labels) ++sizes[label];
  if (std::find(sizes.begin(), sizes.end(), 0) != sizes.end())
    return corrupt("trajectory group: a part holds no vertex");
  head.parts.clear();
  head.multiply_adds = 0;
  for (uint32_t c = 0; c < part_count; ++c) {
    ANIMC_ASSIGN_OR_RETURN(uint32_t length, payload.u32("Part_Length"));
    ANIMC_ASSIGN_OR_RETURN(ByteReader part, payload.subReader(length, "Part"));
    ByteReader fields = part;
    ANIMC_ASSIGN_OR_RETURN(uint16_t part_frames, fields.u16("Frame_Count"));
    ANIMC_ASSIGN_OR_RETURN(uint16_t components, fields.u16("Component_Count"));
    if (part_frames != frames)
      return corrupt("trajectory group: a part of " + std::to_string(part_frames) + " frames in a group of " +
                     std::to_string(frames));
    // Checked again with the part: here it bounds the sum below (64 parts cannot overflow it).
    if (components > uint32_t(3) * frames)
      return corrupt("trajectory group: a part of " + std::to_string(components) + " components and " +
                     std::to_string(frames) + " frames");
    head.multiply_adds += uint64_t(3) * components * sizes[c] * frames;
    head.parts.push_back(part);
  }
  if (payload.remaining() != 0) return corrupt("trajectory group: bytes after the last part");
  return Status();
}

}  // namespace animc
