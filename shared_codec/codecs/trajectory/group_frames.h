// SPDX-License-Identifier: Apache-2.0
// The frames a decoder (and the encoder, for its reconstructions) computes from a trajectory
// group: the group's basis as floats, the frame kernel and the frames of a whole group
// (docs/format.md, section 12.4).
#pragma once
#include <cstdint>

#include "codecs/trajectory/group_coding.h"
#include "core/simd_math.h"
#include "core/uninitialised_vector.h"

namespace animc {

GroupBasis dequantisedBasis(const TrajectoryGroup& group);

// The largest coordinate a decoder hands out, as for the other codecs.
constexpr float kMaxDecodedValue = 1e30f;

// The frames of a group: every decoder and the encoder compute them with these float
// operations in this order, so that they agree to the bit (docs/format.md 12.4). Frames are
// computed kBatch at a time, so that the coefficients are read once for all of them, for
// vertices kLanes at a time (two panels side by side, 2 x kLanes, on the AVX-512 path), from
// panels of their coefficients (K x kLanes floats, a component's kLanes values together; lanes
// past the last vertex are zeros).
struct FrameKernel {
  static constexpr uint32_t kBatch = 4;
  static constexpr uint32_t kLanes = 8;
  // Floats of the panels of `vertices` vertices (rounded up to kLanes), and where vertex v's
  // coefficient of component 0 is in them (component k's is k x kLanes further).
  static size_t panelFloats(uint32_t vertices, uint32_t components) {
    return (size_t(vertices) + kLanes - 1) / kLanes * kLanes * components;
  }
  static size_t panelOffset(uint32_t v, uint32_t components) {
    return size_t(v / kLanes) * components * kLanes + v % kLanes;
  }
  // Frames [first, first + kBatch) (those in the group) of vertices [v_begin, v_end) of
  // `vertices`, v_begin a multiple of kLanes, into out: 3 floats a vertex, `vertices` a frame.
  // Any split of the vertices computes each vertex alike, so threads may share them. Returns
  // the frames (bit f for frame first + f) where one of these vertices has a value that is
  // not finite or above kMaxDecodedValue in size, tracked as the values are written.
  static uint32_t run(SimdPath path, const GroupBasis& basis, const float* panels, uint32_t vertices, uint32_t v_begin,
                      uint32_t v_end, uint32_t first, float* out);
};

// The decoded frames of a whole group.
class GroupFrames {
 public:
  static constexpr uint32_t kBatch = FrameKernel::kBatch;
  static constexpr uint32_t kLanes = FrameKernel::kLanes;

  // The frames of `group` with its mean and basis vectors `basis` (dequantisedBasis(), or as
  // readTrajectoryGroup() decoded them), which are swapped in: `basis` is left with the
  // previous group's, whose buffers the next group may reuse.
  void reset(GroupBasis& basis, const TrajectoryGroup& group, const CodingOrder& order, SimdPath path);
  uint32_t frames() const { return basis_.frames; }
  // Frame t of the group (t < frames()) into xyz (3 floats a vertex, vertex order); false if
  // a value is not finite or above kMaxDecodedValue in size (a damaged group).
  bool frame(uint32_t t, float* xyz) const;
  // The same for a part of a mesh: the group's vertex i into vertex members[i] of xyz.
  bool frameInto(uint32_t t, const uint32_t* members, float* xyz) const;

 private:
  void computeBatch(uint32_t first) const;
  // Frame t's batch computed; where frame t is in it.
  const float* batchFrame(uint32_t t) const;

  SimdPath path_ = SimdPath::kPortable;
  uint32_t vertices_ = 0;
  GroupBasis basis_;
  UninitialisedVector<float> coefficients_;   // panels, vertex order
  mutable UninitialisedVector<float> batch_;  // frames batch_first_ .. + kBatch, 3N floats each
  mutable uint32_t batch_first_ = UINT32_MAX;
  mutable uint32_t batch_damaged_ = 0;  // FrameKernel::run()'s frames with a bad value, of the batch
};

}  // namespace animc
