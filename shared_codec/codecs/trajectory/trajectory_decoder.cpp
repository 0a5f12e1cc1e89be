// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <memory>

#include "codecs/trajectory/group_coding.h"
#include "codecs/trajectory/trajectory_codec.h"

namespace animc {
namespace {

class TrajectoryDecoder final : public FrameDecoder {
 public:
  TrajectoryDecoder(const Topology& topology, uint64_t max_multiply_adds, SimdPath path)
      : topology_(topology), max_multiply_adds_(max_multiply_adds), path_(path) {}

  Status decodeFrame(ByteReader payload, std::vector<float>& xyz, bool* intra) override {
    ANIMC_ASSIGN_OR_RETURN(uint8_t type, payload.u8("Frame_Type"));
    if (type == kTrajectoryGroupFrame) {
      next_ = 0;
      frames_ = GroupFrames();  // a failed read leaves no group to continue
      ANIMC_RETURN_IF_ERROR(readTrajectoryGroup(payload, order(), max_multiply_adds_, group_));
      frames_.reset(group_, order(), path_);
    } else if (type == kTrajectoryNextFrame) {
      if (payload.remaining() != 0) return corrupt("trajectory frame: bytes after the frame type");
      if (next_ >= frames_.frames())
        return corrupt(frames_.frames() == 0 ? "trajectory frame: no group before it"
                                             : "trajectory frame: more frames than its group holds");
    } else {
      return corrupt("trajectory frame: unknown frame type " + std::to_string(type));
    }
    if (intra) *intra = type == kTrajectoryGroupFrame;
    xyz.resize(size_t(topology_.vertex_count) * 3);
    // As for the other codecs: a damaged group may not hand out infinities or huge values.
    if (!frames_.frame(next_++, xyz.data()))
      return corrupt("trajectory frame: a decoded value is not finite or above 1e30");
    return Status();
  }

 private:
  // Made with the first group: the decoder of an auto file holds one for each candidate, and
  // a large mesh's order takes a while to compute.
  const CodingOrder& order() {
    if (!order_) order_ = std::make_unique<const CodingOrder>(topology_);
    return *order_;
  }

  const Topology& topology_;
  std::unique_ptr<const CodingOrder> order_;
  uint64_t max_multiply_adds_;
  SimdPath path_;
  TrajectoryGroup group_;
  GroupFrames frames_;
  uint32_t next_ = 0;
};

}  // namespace

std::unique_ptr<FrameDecoder> makeTrajectoryDecoder(const Topology& topology, const DecoderLimits& limits,
                                                    SimdPath path) {
  return std::make_unique<TrajectoryDecoder>(topology, limits.max_multiply_adds, path);
}

}  // namespace animc
