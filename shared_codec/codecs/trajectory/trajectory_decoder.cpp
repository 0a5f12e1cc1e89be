// SPDX-License-Identifier: Apache-2.0
#include <algorithm>
#include <memory>

#include "codecs/trajectory/group_coding.h"
#include "codecs/trajectory/group_frames.h"
#include "codecs/trajectory/parted_group.h"
#include "codecs/trajectory/trajectory_codec.h"
#include "core/parallel.h"

namespace animc {
namespace {

// The decoder of codecs 3 and 5: a group is one part holding every vertex (codec 3) or
// parts labelled along the mesh, each a codec-3 group of its sub-mesh (codec 5).
class TrajectoryDecoder final : public FrameDecoder {
 public:
  TrajectoryDecoder(const Topology& topology, uint64_t max_multiply_adds, SimdPath path, bool parted)
      : topology_(topology), max_multiply_adds_(max_multiply_adds), path_(path), parted_(parted) {}

  Status decodeFrame(ByteReader payload, std::vector<float>& xyz, bool* intra) override {
    return read(payload, &xyz, intra);
  }
  // Every frame is computed from its group alone, so a frame nobody looks at is not computed.
  Status skipFrame(ByteReader payload, std::vector<float>&, bool* intra) override {
    return read(payload, nullptr, intra);
  }

 private:
  uint32_t groupFrames() const { return frames_.empty() ? 0 : frames_[0].frames(); }

  // Reads one frame record, and computes the frame into *xyz when xyz is not null.
  Status read(ByteReader payload, std::vector<float>* xyz, bool* intra) {
    ANIMC_ASSIGN_OR_RETURN(uint8_t type, payload.u8("Frame_Type"));
    if (type == kTrajectoryGroupFrame) {
      next_ = 0;
      ANIMC_RETURN_IF_ERROR(enterGroup(payload));
    } else if (type == kTrajectoryNextFrame) {
      if (payload.remaining() != 0) return corrupt("trajectory frame: bytes after the frame type");
      if (next_ >= groupFrames())
        return corrupt(groupFrames() == 0 ? "trajectory frame: no group before it"
                                          : "trajectory frame: more frames than its group holds");
    } else {
      return corrupt("trajectory frame: unknown frame type " + std::to_string(type));
    }
    if (intra) *intra = type == kTrajectoryGroupFrame;
    const uint32_t t = next_++;
    if (xyz == nullptr) return Status();
    xyz->resize(size_t(topology_.vertex_count) * 3);
    // As for the other codecs: a damaged group may not hand out infinities or huge values.
    bool finite = true;
    if (!parted_) {
      finite = frames_[0].frame(t, xyz->data());
    } else {
      for (size_t c = 0; c < frames_.size(); ++c)
        finite &= frames_[c].frameInto(t, parts_->members[c].data(), xyz->data());
    }
    if (!finite) return corrupt("trajectory frame: a decoded value is not finite or above 1e30");
    return Status();
  }

  // A random access that goes back into the group decoded last meets the same payload again:
  // the same bytes make the same group, so it is kept rather than decoded again.
  Status enterGroup(ByteReader payload) {
    const uint8_t* bytes = payload.cursor();
    const size_t size = payload.remaining();
    if (groupFrames() > 0 && size == group_payload_.size() && std::equal(bytes, bytes + size, group_payload_.begin()))
      return Status();
    frames_.clear();  // a failed read leaves no group to continue
    group_payload_.clear();
    ANIMC_RETURN_IF_ERROR(parted_ ? readParts(payload) : readWhole(payload));
    group_payload_.assign(bytes, bytes + size);
    return Status();
  }

  Status readWhole(ByteReader payload) {
    groups_.resize(1);
    bases_.resize(1);
    TrajectoryGroup& group = groups_[0];
    // The order is made with the first group: the decoder of an auto file holds one for each
    // candidate, and a large mesh's order takes a while to compute.
    if (order_) {
      ANIMC_RETURN_IF_ERROR(readTrajectoryGroup(payload, *order_, max_multiply_adds_, group, &bases_[0]));
    } else {
      ANIMC_RETURN_IF_ERROR(
          walkAndReadTrajectoryGroup(topology_, payload, max_multiply_adds_, order_, group, &bases_[0]));
    }
    frames_.resize(1);
    frames_[0].reset(bases_[0], group, *order_, path_);
    return Status();
  }

  // The labels, then the parts on any thread (each its own coded data); the first failing
  // part's error, in part order, whatever the thread count.
  Status readParts(ByteReader payload) {
    if (!order_) order_ = std::make_unique<const CodingOrder>(topology_);
    PartedGroupHead head;
    ANIMC_RETURN_IF_ERROR(readPartedGroupHead(payload, *order_, head));
    if (head.multiply_adds > max_multiply_adds_)
      return multiplyAddsAboveLimit("trajectory group of " + std::to_string(head.part_count) + " parts",
                                    head.multiply_adds, max_multiply_adds_);
    parts_ = std::make_unique<MeshParts>(topology_, head.labels, head.part_count);
    groups_.resize(head.part_count);
    bases_.resize(head.part_count);
    std::vector<Status> read(head.part_count);
    parallelFor(head.part_count, [&](size_t c) {
      read[c] = readTrajectoryGroup(head.parts[c], *parts_->orders[c], max_multiply_adds_, groups_[c], &bases_[c]);
    });
    for (const Status& s : read) ANIMC_RETURN_IF_ERROR(s);
    frames_.resize(head.part_count);
    for (uint32_t c = 0; c < head.part_count; ++c) frames_[c].reset(bases_[c], groups_[c], *parts_->orders[c], path_);
    return Status();
  }

  const Topology& topology_;
  std::unique_ptr<const CodingOrder> order_;  // of the whole mesh
  uint64_t max_multiply_adds_;
  SimdPath path_;
  bool parted_;
  std::unique_ptr<MeshParts> parts_;    // of the group decoded last (codec 5)
  // Each part's integers and its basis as floats, read here group after group: their buffers
  // stay (a large group's would otherwise be new pages every group). A basis is swapped with
  // the one its frames_ held.
  std::vector<TrajectoryGroup> groups_;
  std::vector<GroupBasis> bases_;
  std::vector<GroupFrames> frames_;     // of each part, of the group decoded last
  std::vector<uint8_t> group_payload_;  // of frames_, after its Frame_Type
  uint32_t next_ = 0;
};

}  // namespace

std::unique_ptr<FrameDecoder> makeTrajectoryDecoder(const Topology& topology, const DecoderLimits& limits,
                                                    SimdPath path) {
  return std::make_unique<TrajectoryDecoder>(topology, limits.max_multiply_adds, path, false);
}

std::unique_ptr<FrameDecoder> makeTrajectory2Decoder(const Topology& topology, const DecoderLimits& limits,
                                                     SimdPath path) {
  return std::make_unique<TrajectoryDecoder>(topology, limits.max_multiply_adds, path, true);
}

}  // namespace animc
