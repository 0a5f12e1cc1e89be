// SPDX-License-Identifier: Apache-2.0
// One frame group of the trajectory codec as integers (what the payload carries), its
// payload, and the frames a decoder makes of it (docs/format.md, section 12).
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/sequence.h"
#include "core/simd_math.h"
#include "core/status.h"
#include "core/uninitialised_vector.h"
#include "io/byte_reader.h"

namespace animc {

// The order vertices are coded in (breadth-first over the mesh edges from vertex 0, each
// vertex's neighbours in index order, then the next unreached vertex) and, for each position
// in it, the positions of the neighbours coded before it: they predict its coefficients.
struct CodingOrder {
  explicit CodingOrder(const Topology& topology);
  UninitialisedVector<uint32_t> vertex;   // vertex at each position
  UninitialisedVector<uint32_t> first;    // earlier[first[p] .. first[p + 1]) for position p
  UninitialisedVector<uint32_t> earlier;  // positions
};

// The group as coded. Trajectory rows are 3G long: x over the G frames, then y, then z.
struct TrajectoryGroup {
  uint32_t frames = 0;      // G
  uint32_t components = 0;  // K
  float coefficient_step = 0;
  float mean_step = 0;
  std::vector<int32_t> mean;          // 3G, in units of mean_step
  std::vector<float> basis_step;      // K
  std::vector<int32_t> basis;         // K rows of 3G, in units of their basis_step
  UninitialisedVector<int32_t> coefficients;  // per coding position, K values, in units of coefficient_step
};

// Components are coded in bands of doubling width (0, 1, 2-3, 4-7, ..., the last one open):
// the first carry most of the motion and so the largest values. A component's band picks the
// models of its basis vector and of its coefficients.
constexpr int kCoefficientBands = 8;
inline int coefficientBand(uint32_t k) { return std::min(31 - __builtin_clz(k + 1), kCoefficientBands - 1); }
// The rounded mean of n > 0 values summing to `sum` (half away from -infinity): a
// coefficient's prediction from its coded neighbours.
inline int64_t roundedMean(int64_t sum, int64_t n) {
  const int64_t numerator = 2 * sum + n, denominator = 2 * n;
  return numerator / denominator - ((numerator % denominator) < 0 ? 1 : 0);
}

// Frame_Type, the payload's first byte.
constexpr uint8_t kTrajectoryGroupFrame = 0;  // the group's first frame: the whole group
constexpr uint8_t kTrajectoryNextFrame = 1;   // the group's next frame: nothing else

void writeTrajectoryGroup(const TrajectoryGroup& group, const CodingOrder& order, std::vector<uint8_t>& out);
// Reads a group payload after its Frame_Type byte; a group whose reconstruction would cost more
// than max_multiply_adds (3 x components x vertices x frames) is refused before any decoding.
Status readTrajectoryGroup(ByteReader payload, const CodingOrder& order, uint64_t max_multiply_adds,
                           TrajectoryGroup& group);

// A group's mean and basis vectors as the decoders compute with them (docs/format.md 12.4).
struct GroupBasis {
  uint32_t frames = 0;
  uint32_t components = 0;
  UninitialisedVector<float> mean;   // 3G
  UninitialisedVector<float> basis;  // K rows of 3G
};
GroupBasis dequantisedBasis(const TrajectoryGroup& group);

// The largest coordinate a decoder hands out, as for the other codecs.
constexpr float kMaxDecodedValue = 1e30f;

// A quantised coefficient as the decoders multiply with it.
inline float dequantisedCoefficient(int32_t value, float step) { return float(value) * step; }

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

  void reset(const TrajectoryGroup& group, const CodingOrder& order, SimdPath path);
  uint32_t frames() const { return basis_.frames; }
  // Frame t of the group (t < frames()) into xyz (3 floats a vertex, vertex order); false if
  // a value is not finite or above kMaxDecodedValue in size (a damaged group).
  bool frame(uint32_t t, float* xyz) const;

 private:
  void computeBatch(uint32_t first) const;

  SimdPath path_ = SimdPath::kPortable;
  uint32_t vertices_ = 0;
  GroupBasis basis_;
  UninitialisedVector<float> coefficients_;   // panels, vertex order
  mutable UninitialisedVector<float> batch_;  // frames batch_first_ .. + kBatch, 3N floats each
  mutable uint32_t batch_first_ = UINT32_MAX;
  mutable uint32_t batch_damaged_ = 0;  // FrameKernel::run()'s frames with a bad value, of the batch
};

}  // namespace animc
