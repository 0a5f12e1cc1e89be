// SPDX-License-Identifier: Apache-2.0
// One frame group of the trajectory codec as integers (what the payload carries), its
// payload and the order its vertices are coded in (docs/format.md, section 12). The frames a
// decoder makes of it are in group_frames.h.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/adjacency.h"
#include "core/sequence.h"
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

  // The order in storage sized once for its adjacency, so that another thread may read the
  // positions done while walk() writes the next ones.
  explicit CodingOrder(const VertexAdjacency& adjacency);
  // Walks the order, once; when `done` is not null, stores there (released) how many positions
  // are done (their vertex and earlier positions written) as it goes. It allocates nothing, so
  // a reader waiting for it cannot be left waiting by a failure.
  void walk(const VertexAdjacency& adjacency, std::atomic<uint32_t>* done);

 private:
  UninitialisedVector<uint32_t> position_;  // of each vertex, until the walk ends
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

// A group's mean and basis vectors as the decoders compute with them (docs/format.md 12.4).
struct GroupBasis {
  uint32_t frames = 0;
  uint32_t components = 0;
  UninitialisedVector<float> mean;   // 3G
  UninitialisedVector<float> basis;  // K rows of 3G
};

// A quantised value (a mean, basis or coefficient value in units of its step) as the decoders
// compute with it (docs/format.md 12.4).
inline float dequantised(int32_t value, float step) { return float(value) * step; }

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
// The same without Frame_Type: what readTrajectoryGroup() reads (a part of a codec-5 group).
void writeTrajectoryGroupFields(const TrajectoryGroup& group, const CodingOrder& order, std::vector<uint8_t>& out);
// The error of a group whose reconstruction (`what`) costs `work` multiply-adds, above `limit`.
Status multiplyAddsAboveLimit(const std::string& what, uint64_t work, uint64_t limit);

// Reads a group payload after its Frame_Type byte; a group whose reconstruction would cost more
// than max_multiply_adds (3 x components x vertices x frames) is refused before any decoding.
// `done`, when not null, is a walk's count of the positions of `order` done so far: the reading
// waits for each position to be done (CodingOrder::walk).
// When `basis` is not null, the mean and basis vectors go there as floats, each value
// dequantised as it is decoded, and group.mean and group.basis are left empty: a decoder
// holds them once, not also as integers.
Status readTrajectoryGroup(ByteReader payload, const CodingOrder& order, uint64_t max_multiply_adds,
                           TrajectoryGroup& group, GroupBasis* basis = nullptr,
                           const std::atomic<uint32_t>* done = nullptr);
// The coding order of `topology` into `order`, and the group of `payload` read with it: the
// order is walked on a second thread when the budget allows, and the reading follows it
// position by position. `order` is complete even when the group is not read. `basis` as for
// readTrajectoryGroup().
Status walkAndReadTrajectoryGroup(const Topology& topology, ByteReader payload, uint64_t max_multiply_adds,
                                  std::unique_ptr<const CodingOrder>& order, TrajectoryGroup& group,
                                  GroupBasis* basis = nullptr);

}  // namespace animc
