// SPDX-License-Identifier: Apache-2.0
#include "codecs/trajectory/group_frames.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "core/parallel.h"

namespace animc {
namespace {

// Vertices a thread takes at a time when the panels are filled or a batch is computed.
constexpr uint32_t kVerticesPerTask = 4096;

}  // namespace

GroupBasis dequantisedBasis(const TrajectoryGroup& g) {
  GroupBasis b;
  b.frames = g.frames;
  b.components = g.components;
  const size_t row = size_t(3) * g.frames;
  b.mean.resize(row);
  for (size_t i = 0; i < row; ++i) b.mean[i] = dequantised(g.mean[i], g.mean_step);
  b.basis.resize(g.components * row);
  for (uint32_t k = 0; k < g.components; ++k)
    for (size_t i = 0; i < row; ++i) b.basis[k * row + i] = dequantised(g.basis[k * row + i], g.basis_step[k]);
  return b;
}

void GroupFrames::reset(GroupBasis& basis, const TrajectoryGroup& g, const CodingOrder& order, SimdPath path) {
  path_ = path;
  std::swap(basis_, basis);
  vertices_ = uint32_t(order.vertex.size());
  const uint32_t components = g.components;
  // Panels: a kernel step reads one front to back instead of K rows far apart. Each vertex is
  // at one position, so the positions fill every lane but those past the last vertex.
  coefficients_.resize(FrameKernel::panelFloats(vertices_, components));
  for (size_t i = FrameKernel::panelOffset(vertices_ & ~(kLanes - 1), components); i < coefficients_.size(); ++i)
    if (i % kLanes >= vertices_ % kLanes) coefficients_[i] = 0.0f;
  parallelForBlocks(vertices_, kVerticesPerTask, components, [&](size_t, size_t begin, size_t end) {
    for (size_t p = begin; components > 0 && p < end; ++p) {
      float* panel = coefficients_.data() + FrameKernel::panelOffset(order.vertex[p], components);
      const int32_t* c = g.coefficients.data() + p * components;
      for (uint32_t k = 0; k < components; ++k)
        panel[size_t(k) * kLanes] = dequantised(c[k], g.coefficient_step);
    }
  });
  batch_.resize(size_t(kBatch) * 3 * vertices_);
  batch_first_ = UINT32_MAX;
}

namespace {

using Floats8 = float __attribute__((vector_size(32)));
using Bits8 = uint32_t __attribute__((vector_size(32)));
using Floats16 = float __attribute__((vector_size(64)));
using Bits16 = uint32_t __attribute__((vector_size(64)));

// The coefficients of component k of the vertices of one kernel step: one panel's lanes, or
// (16 lanes) those of two panels side by side, the next 8 vertices. (Through a reference: a
// vector passed by value would change the calling convention of the functions around it.)
__attribute__((always_inline)) inline void loadPanel(const float* panel, uint32_t, uint32_t k, Floats8& c) {
  std::memcpy(&c, panel + size_t(k) * FrameKernel::kLanes, sizeof c);  // an unaligned load
}
__attribute__((always_inline)) inline void loadPanel(const float* panel, uint32_t components, uint32_t k, Floats16& c) {
  Floats8 low, high;
  loadPanel(panel, components, k, low);
  loadPanel(panel + size_t(components) * FrameKernel::kLanes, components, k, high);
  c = __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
}

// The sums of kBatch frames (from `first`) for the vertices of one kernel step (8 or 16 lanes
// of Vec), component by component: each lane does the same float multiply and add in the same
// order, whatever the width of the operations the compiler makes of them.
template <class Vec>
__attribute__((always_inline)) inline void sumLanes(const float* panel, const float* basis, uint32_t components,
                                                    uint32_t frames, uint32_t first, Vec sums[][3]) {
  constexpr uint32_t kBatch = FrameKernel::kBatch;
  uint32_t column[kBatch];  // frames past the group repeat its last one, and are not stored
  for (uint32_t f = 0; f < kBatch; ++f) column[f] = std::min(first + f, frames - 1);
  for (uint32_t f = 0; f < kBatch; ++f)
    for (int d = 0; d < 3; ++d) sums[f][d] = Vec{};
  const size_t row = size_t(3) * frames;
  for (uint32_t k = 0; k < components; ++k) {
    Vec c;
    loadPanel(panel, components, k, c);
    const float* b = basis + k * row;
    for (uint32_t f = 0; f < kBatch; ++f)
      for (uint32_t d = 0; d < 3; ++d) sums[f][d] += c * b[d * frames + column[f]];
  }
}

inline uint32_t bitsOf(float value) {
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

// One kernel step: the vertices from v0 (lanes of them, the rest of Vec's lanes past the
// last vertex or, with 16 lanes, past v_end) of kBatch frames from `first` into out; `largest`
// keeps, per frame and lane, the largest bits of a value's magnitude written.
template <class Vec, class Bits>
__attribute__((always_inline)) inline void kernelStep(const float* coefficients, const float* basis, const float* mean,
                                                      uint32_t components, uint32_t frames, uint32_t vertices,
                                                      uint32_t v0, uint32_t lanes, uint32_t first, float* out,
                                                      Bits largest[]) {
  constexpr uint32_t kBatch = FrameKernel::kBatch, kWidth = sizeof(Vec) / sizeof(float);
  Vec sums[kBatch][3];
  sumLanes(coefficients + size_t(v0) * components, basis, components, frames, first, sums);
  Bits vertex_lanes = ~Bits{};  // the lanes past the last vertex hold no vertex's value: not counted
  if (lanes < kWidth)
    for (uint32_t l = lanes; l < kWidth; ++l) vertex_lanes[l] = 0;
  const uint32_t count = std::min(kBatch, frames - first);
  for (uint32_t f = 0; f < count; ++f) {
    float* xyz = out + (size_t(f) * vertices + v0) * 3;
    for (uint32_t d = 0; d < 3; ++d) {
      const Vec values = mean[d * frames + first + f] + sums[f][d];
      // The bits of |value|, a vector cast: the larger magnitude has the larger bits, and a
      // NaN or an infinity more than any finite float.
      const Bits magnitude = Bits(values) & 0x7FFFFFFFu & vertex_lanes;
      largest[f] = magnitude > largest[f] ? magnitude : largest[f];
      for (uint32_t l = 0; l < lanes; ++l) xyz[3 * l + d] = values[l];
    }
  }
}

// The frames of kBatch (bit f for first + f) with a value that is not finite or above
// kMaxDecodedValue in size.
template <class Bits>
uint32_t damagedFrames(const Bits largest[], uint32_t count) {
  const uint32_t limit = bitsOf(kMaxDecodedValue);
  uint32_t damaged = 0;
  for (uint32_t f = 0; f < count; ++f)
    for (uint32_t l = 0; l < sizeof(Bits) / sizeof(uint32_t); ++l)
      if (largest[f][l] > limit) damaged |= 1u << f;
  return damaged;
}

// Vertices [v_begin, v_end) of kBatch frames from `first` (v_begin a multiple of kLanes), Vec's
// lanes a step (the last step of 16 lanes and fewer than 9 vertices takes 8): any split of the
// vertices computes each lane alike, so threads may share them. Returns FrameKernel::run()'s
// mask of frames with a bad value.
template <class Vec, class Bits>
__attribute__((always_inline)) inline uint32_t batchKernel(const float* coefficients, const float* basis,
                                                           const float* mean, uint32_t components, uint32_t frames,
                                                           uint32_t vertices, uint32_t v_begin, uint32_t v_end,
                                                           uint32_t first, float* out) {
  constexpr uint32_t kBatch = FrameKernel::kBatch, kLanes = FrameKernel::kLanes;
  constexpr uint32_t kWidth = sizeof(Vec) / sizeof(float);
  Bits largest[kBatch] = {};
  Bits8 largest8[kBatch] = {};
  uint32_t v0 = v_begin;
  // A step of 16 lanes reads a second panel: only where it holds a vertex, so that it exists.
  for (; v0 + (kWidth - kLanes) < v_end; v0 += kWidth)
    kernelStep<Vec>(coefficients, basis, mean, components, frames, vertices, v0, std::min(kWidth, v_end - v0), first,
                    out, largest);
  for (; v0 < v_end; v0 += kLanes)
    kernelStep<Floats8>(coefficients, basis, mean, components, frames, vertices, v0, std::min(kLanes, v_end - v0),
                        first, out, largest8);
  const uint32_t count = std::min(kBatch, frames - first);
  return damagedFrames(largest, count) | damagedFrames(largest8, count);
}

__attribute__((noinline)) uint32_t batchPortable(const float* c, const float* b, const float* m, uint32_t k, uint32_t g,
                                                 uint32_t n, uint32_t v_begin, uint32_t v_end, uint32_t first,
                                                 float* out) {
  return batchKernel<Floats8, Bits8>(c, b, m, k, g, n, v_begin, v_end, first, out);
}

#ifndef ANIMC_NO_AVX2
ANIMC_TARGET_AVX2 __attribute__((noinline)) uint32_t batchAvx2(const float* c, const float* b, const float* m,
                                                               uint32_t k, uint32_t g, uint32_t n, uint32_t v_begin,
                                                               uint32_t v_end, uint32_t first, float* out) {
  return batchKernel<Floats8, Bits8>(c, b, m, k, g, n, v_begin, v_end, first, out);
}

ANIMC_TARGET_AVX512 __attribute__((noinline)) uint32_t batchAvx512(const float* c, const float* b, const float* m,
                                                                   uint32_t k, uint32_t g, uint32_t n, uint32_t v_begin,
                                                                   uint32_t v_end, uint32_t first, float* out) {
  return batchKernel<Floats16, Bits16>(c, b, m, k, g, n, v_begin, v_end, first, out);
}
#endif

}  // namespace

uint32_t FrameKernel::run(SimdPath path, const GroupBasis& b, const float* panels, uint32_t vertices, uint32_t v_begin,
                          uint32_t v_end, uint32_t first, float* out) {
#ifndef ANIMC_NO_AVX2
  if (path == SimdPath::kAvx512)
    return batchAvx512(panels, b.basis.data(), b.mean.data(), b.components, b.frames, vertices, v_begin, v_end, first,
                       out);
  if (path == SimdPath::kAvx2)
    return batchAvx2(panels, b.basis.data(), b.mean.data(), b.components, b.frames, vertices, v_begin, v_end, first,
                     out);
#endif
  return batchPortable(panels, b.basis.data(), b.mean.data(), b.components, b.frames, vertices, v_begin, v_end, first,
                       out);
}

void GroupFrames::computeBatch(uint32_t first) const {
  const double vertex_cost = double(basis_.components) * kBatch * 3;
  std::vector<uint32_t> damaged((vertices_ + kVerticesPerTask - 1) / kVerticesPerTask, 0);
  parallelForBlocks(vertices_, kVerticesPerTask, vertex_cost, [&](size_t block, size_t begin, size_t end) {
    damaged[block] = FrameKernel::run(path_, basis_, coefficients_.data(), vertices_, uint32_t(begin), uint32_t(end),
                                      first, batch_.data());
  });
  batch_damaged_ = 0;
  for (uint32_t mask : damaged) batch_damaged_ |= mask;
  batch_first_ = first;
}

const float* GroupFrames::batchFrame(uint32_t t) const {
  if (batch_first_ == UINT32_MAX || t >= batch_first_ + kBatch) {
    computeBatch(t);
  } else if (t < batch_first_) {  // going backwards: the batch ends at t, for the frames before it
    computeBatch(t >= kBatch - 1 ? t - (kBatch - 1) : 0);
  }
  return &batch_[(t - batch_first_) * size_t(3) * vertices_];
}

bool GroupFrames::frame(uint32_t t, float* xyz) const {
  copyOnThreads(batchFrame(t), size_t(3) * vertices_, xyz);
  return ((batch_damaged_ >> (t - batch_first_)) & 1) == 0;
}

bool GroupFrames::frameInto(uint32_t t, const uint32_t* members, float* xyz) const {
  const float* values = batchFrame(t);
  for (uint32_t i = 0; i < vertices_; ++i)
    for (int d = 0; d < 3; ++d) xyz[size_t(members[i]) * 3 + d] = values[size_t(i) * 3 + d];
  return ((batch_damaged_ >> (t - batch_first_)) & 1) == 0;
}

}  // namespace animc
