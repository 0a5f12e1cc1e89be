// SPDX-License-Identifier: Apache-2.0
#include <algorithm>
#include <memory>

#include "codecs/trajectory/group_coding.h"
#include "codecs/trajectory/group_frames.h"
#include "codecs/trajectory/trajectory_codec.h"

namespace animc {
namespace {

class TrajectoryDecoder final : public FrameDecoder {
 public:
  TrajectoryDecoder(const Topology& topology, uint64_t max_multiply_adds, SimdPath path)
      : topology_(topology), max_multiply_adds_(max_multiply_adds), path_(path) {}

  Status decodeFrame(ByteReader payload, std::vector<float>& xyz, bool* intra) override {
    return read(payload, &xyz, intra);
  }
  // Every frame is computed from its group alone, so a frame nobody looks at is not computed.
  Status skipFrame(ByteReader payload, std::vector<float>&, bool* intra) override {
    return read(payload, nullptr, intra);
  }

 private:
  // Reads one frame record, and computes the frame into *xyz when xyz is not null.
  Status read(ByteReader payload, std::vector<float>* xyz, bool* intra) {
    ANIMC_ASSIGN_OR_RETURN(uint8_t type, payload.u8("Frame_Type"));
    if (type == kTrajectoryGroupFrame) {
      next_ = 0;
      ANIMC_RETURN_IF_ERROR(enterGroup(payload));
    } else if (type == kTrajectoryNextFrame) {
      if (payload.remaining() != 0) return corrupt("trajectory frame: bytes after the frame type");
      if (next_ >= frames_.frames())
        return corrupt(frames_.frames() == 0 ? "trajectory frame: no group before it"
                                             : "trajectory frame: more frames than its group holds");
    } else {
      return corrupt("trajectory frame: unknown frame type " + std::to_string(type));
    }
    if (intra) *intra = type == kTrajectoryGroupFrame;
    const uint32_t t = next_++;
    if (xyz == nullptr) return Status();
    xyz->resize(size_t(topology_.vertex_count) * 3);
    // As for the other codecs: a damaged group may not hand out infinities or huge values.
    if (!frames_.frame(t, xyz->data())) return corrupt("trajectory frame: a decoded value is not finite or above 1e30");
    return Status();
  }

  // A random access that goes back into the group decoded last meets the same payload again:
  // the same bytes make the same group, so it is kept rather than decoded again.
  Status enterGroup(ByteReader payload) {
    const uint8_t* bytes = payload.cursor();
    const size_t size = payload.remaining();
    if (frames_.frames() > 0 && size == group_payload_.size() &&
        std::equal(bytes, bytes + size, group_payload_.begin()))
      return Status();
    frames_ = GroupFrames();  // a failed read leaves no group to continue
    group_payload_.clear();
    // The order is made with the first group: the decoder of an auto file holds one for each
    // candidate, and a large mesh's order takes a while to compute.
    if (order_) {
      ANIMC_RETURN_IF_ERROR(readTrajectoryGroup(payload, *order_, max_multiply_adds_, group_));
    } else {
      ANIMC_RETURN_IF_ERROR(walkAndReadTrajectoryGroup(topology_, payload, max_multiply_adds_, order_, group_));
    }
    frames_.reset(group_, *order_, path_);
    group_payload_.assign(bytes, bytes + size);
    return Status();
  }

  const Topology& topology_;
  std::unique_ptr<const CodingOrder> order_;
  uint64_t max_multiply_adds_;
  SimdPath path_;
  TrajectoryGroup group_;
  GroupFrames frames_;
  std::vector<uint8_t> group_payload_;  // of frames_, after its Frame_Type
  uint32_t next_ = 0;
};

}  // namespace

std::unique_ptr<FrameDecoder> makeTrajectoryDecoder(const Topology& topology, const DecoderLimits& limits,
                                                    SimdPath path) {
  return std::make_unique<TrajectoryDecoder>(topology, limits.max_multiply_adds, path);
}

}  // namespace animc
