// SPDX-License-Identifier: Apache-2.0
#include "codecs/trajectory/group_coding.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "codecs/trajectory/options.h"
#include "core/adjacency.h"
#include "core/parallel.h"
#include "entropy/classed_integer.h"
#include "io/byte_writer.h"

namespace animc {
namespace {

// A coefficient's context: its component's band, and what its prediction says (no coded
// neighbour, a zero prediction, a non-zero one).
constexpr int kPredictionKinds = 3;

struct GroupModels {
  ClassedIntegerModel mean;
  ClassedIntegerModel basis[kCoefficientBands];
  ClassedIntegerModel coefficient[kCoefficientBands * kPredictionKinds];
};

// A coefficient's prediction and the context it gives.
struct Prediction {
  int64_t value = 0;
  int kind = 0;
};

// The predictions of every component of the vertex at one coding position: the rounded mean
// of its earlier neighbours' values (half away from -infinity), and the context each gives.
// The neighbours' rows are summed whole, once for all components.
class Predictions {
 public:
  explicit Predictions(uint32_t components) : sum_(components), components_(components) {}

  void at(const CodingOrder& order, const int32_t* values, uint32_t position) {
    const uint32_t begin = order.first[position], end = order.first[position + 1];
    count_ = end - begin;
    std::fill(sum_.begin(), sum_.end(), 0);
    for (uint32_t i = begin; i < end; ++i) {
      const int32_t* row = values + size_t(order.earlier[i]) * components_;
      for (uint32_t k = 0; k < components_; ++k) sum_[k] += row[k];
    }
  }
  Prediction operator[](uint32_t k) const {
    if (count_ == 0) return {};
    const int64_t mean = roundedMean(sum_[k], count_);
    return {mean, mean == 0 ? 1 : 2};
  }

 private:
  std::vector<int64_t> sum_;
  uint32_t components_;
  int64_t count_ = 0;
};

// Values coded as differences along time within each of the three coordinate runs of a
// trajectory row, which are smooth.
void encodeRow(RangeEncoder& rc, RawBitWriter& raw, ClassedIntegerModel& m, const int32_t* row, uint32_t frames) {
  for (uint32_t c = 0; c < 3; ++c) {
    int64_t previous = 0;
    for (uint32_t t = 0; t < frames; ++t) {
      const int64_t v = row[c * frames + t];
      encodeClassed(rc, raw, m, v - previous);
      previous = v;
    }
  }
}

bool fitsInt32(int64_t v) { return v >= INT32_MIN && v <= INT32_MAX; }

bool decodeRow(RangeDecoder& rc, RawBitReader& raw, ClassedIntegerModel& m, int32_t* row, uint32_t frames) {
  for (uint32_t c = 0; c < 3; ++c) {
    int64_t previous = 0;
    for (uint32_t t = 0; t < frames; ++t) {
      const int64_t v = previous + decodeClassed(rc, raw, m);
      if (!fitsInt32(v)) return false;
      row[c * frames + t] = int32_t(v);
      previous = v;
    }
  }
  return true;
}

bool usableStep(float s) { return std::isfinite(s) && s > 0; }

// Vertices a thread takes at a time when the panels are filled or a batch is computed.
constexpr uint32_t kVerticesPerTask = 4096;

}  // namespace

CodingOrder::CodingOrder(const Topology& topology) {
  const uint32_t n = topology.vertex_count;
  const VertexAdjacency adjacency(topology);
  UninitialisedVector<uint32_t> position(n, UINT32_MAX);
  vertex.reserve(n);
  // The vertices placed so far are the breadth-first queue: those from `next` on are waiting.
  auto place = [&](uint32_t v) {
    position[v] = uint32_t(vertex.size());
    vertex.push_back(v);
  };
  for (uint32_t root = 0; root < n; ++root) {
    if (position[root] != UINT32_MAX) continue;
    place(root);
    for (size_t next = vertex.size() - 1; next < vertex.size(); ++next) {
      const uint32_t v = vertex[next];
      for (const uint32_t* w = adjacency.begin(v); w != adjacency.end(v); ++w)
        if (position[*w] == UINT32_MAX) place(*w);
    }
  }
  // Only the walk above is serial. Each position's earlier neighbours are listed on threads:
  // counted, summed into `first`, then written in place, the same lists on any thread count.
  auto forEarlier = [&](uint32_t p, const auto& visit) {
    const uint32_t v = vertex[p];
    for (const uint32_t* w = adjacency.begin(v); w != adjacency.end(v); ++w)
      if (position[*w] < p) visit(position[*w]);
  };
  first.assign(size_t(n) + 1, 0);
  parallelForBlocks(n, kVerticesPerTask, 20, [&](size_t, size_t begin, size_t end) {
    for (size_t p = begin; p < end; ++p) forEarlier(uint32_t(p), [&](uint32_t) { ++first[p + 1]; });
  });
  for (uint32_t p = 0; p < n; ++p) first[p + 1] += first[p];
  earlier.resize(first[n]);
  parallelForBlocks(n, kVerticesPerTask, 20, [&](size_t, size_t begin, size_t end) {
    for (size_t p = begin; p < end; ++p) {
      uint32_t* out = earlier.data() + first[p];
      forEarlier(uint32_t(p), [&](uint32_t q) { *out++ = q; });
    }
  });
}

void writeTrajectoryGroup(const TrajectoryGroup& g, const CodingOrder& order, std::vector<uint8_t>& out) {
  ByteWriter head;
  head.u8(kTrajectoryGroupFrame);
  head.u16(uint16_t(g.frames));
  head.u16(uint16_t(g.components));
  head.f32(g.coefficient_step);
  head.f32(g.mean_step);
  for (float s : g.basis_step) head.f32(s);
  out.insert(out.end(), head.bytes().begin(), head.bytes().end());

  auto models = std::make_unique<GroupModels>();
  RangeEncoder rc(out);
  RawBitWriter raw;
  encodeRow(rc, raw, models->mean, g.mean.data(), g.frames);
  const size_t row = size_t(3) * g.frames;
  for (uint32_t k = 0; k < g.components; ++k)
    encodeRow(rc, raw, models->basis[coefficientBand(k)], g.basis.data() + k * row, g.frames);
  const uint32_t n = uint32_t(order.vertex.size());
  Predictions predictions(g.components);
  for (uint32_t p = 0; p < n; ++p) {
    predictions.at(order, g.coefficients.data(), p);
    for (uint32_t k = 0; k < g.components; ++k) {
      const Prediction pred = predictions[k];
      const int64_t v = g.coefficients[size_t(p) * g.components + k];
      encodeClassed(rc, raw, models->coefficient[coefficientBand(k) * kPredictionKinds + pred.kind], v - pred.value);
    }
  }
  rc.finish();
  raw.appendTo(out);
}

Status readTrajectoryGroup(ByteReader payload, const CodingOrder& order, uint64_t max_multiply_adds,
                           TrajectoryGroup& g) {
  const uint64_t n = order.vertex.size();
  ANIMC_ASSIGN_OR_RETURN(uint16_t frames, payload.u16("Frame_Count"));
  ANIMC_ASSIGN_OR_RETURN(uint16_t components, payload.u16("Component_Count"));
  if (frames < 1 || frames > kMaxTrajectoryGroupFrames)
    return corrupt("trajectory group of " + std::to_string(frames) + " frames, outside [1, " +
                   std::to_string(kMaxTrajectoryGroupFrames) + "]");
  if (components > std::min<uint64_t>(n, uint64_t(3) * frames) || components * n > kMaxTrajectoryCoefficients)
    return corrupt("trajectory group of " + std::to_string(components) + " components for " + std::to_string(n) +
                   " vertices and " + std::to_string(frames) + " frames");
  // Below 2^25 coefficients and 2^10 frames the product cannot wrap, and it stays below the
  // default limit: every group the encoder writes decodes with the default limits.
  static_assert(3 * kMaxTrajectoryCoefficients * kMaxTrajectoryGroupFrames <= DecoderLimits{}.max_multiply_adds,
                "the largest group must be within the default limit");
  const uint64_t work = uint64_t(3) * components * n * frames;
  if (work > max_multiply_adds)
    return limitExceeded("trajectory group of " + std::to_string(components) + " components, " + std::to_string(n) +
                         " vertices and " + std::to_string(frames) + " frames costs " + std::to_string(work) +
                         " multiply-adds, above the limit of " + std::to_string(max_multiply_adds) +
                         "; raise it for a trusted file (DecoderLimits::max_multiply_adds, animc --max-multiply-adds)");
  g.frames = frames;
  g.components = components;
  ANIMC_ASSIGN_OR_RETURN(g.coefficient_step, payload.f32("Coefficient_Step"));
  ANIMC_ASSIGN_OR_RETURN(g.mean_step, payload.f32("Mean_Step"));
  g.basis_step.resize(components);
  for (float& step : g.basis_step) {
    ANIMC_ASSIGN_OR_RETURN(step, payload.f32("Basis_Step"));
  }
  if (!usableStep(g.coefficient_step) || !usableStep(g.mean_step) ||
      !std::all_of(g.basis_step.begin(), g.basis_step.end(), usableStep))
    return corrupt("trajectory group: a step is not a positive finite number");

  const size_t row = size_t(3) * frames;
  // Every value is decoded below (a failed decode leaves the group unusable anyway).
  g.mean.resize(row);
  g.basis.resize(components * row);
  g.coefficients.resize(n * components);
  auto models = std::make_unique<GroupModels>();
  RangeDecoder rc(payload.cursor(), payload.remaining());
  RawBitReader raw(payload.cursor(), payload.remaining());
  bool fits = decodeRow(rc, raw, models->mean, g.mean.data(), frames);
  for (uint32_t k = 0; fits && k < components; ++k)
    fits = decodeRow(rc, raw, models->basis[coefficientBand(k)], g.basis.data() + k * row, frames);
  // Damaged data is found at the end: the loops are as long whatever the bytes, and a
  // decoder that reads past its input gets zeros.
  Predictions predictions(components);
  for (uint32_t p = 0; fits && p < n; ++p) {
    predictions.at(order, g.coefficients.data(), p);
    for (uint32_t k = 0; k < components; ++k) {
      const Prediction pred = predictions[k];
      const int64_t v =
          pred.value + decodeClassed(rc, raw, models->coefficient[coefficientBand(k) * kPredictionKinds + pred.kind]);
      if (!fitsInt32(v)) fits = false;
      g.coefficients[size_t(p) * components + k] = int32_t(v);
    }
  }
  const size_t coded_bytes = size_t(rc.position() - payload.cursor());
  if (!fits || rc.overran() || raw.overran() || coded_bytes + raw.bytesUsed() > payload.remaining() + kFinishReadAhead)
    return corrupt("trajectory group: coded data ends early or is damaged");
  return Status();
}

GroupBasis dequantisedBasis(const TrajectoryGroup& g) {
  GroupBasis b;
  b.frames = g.frames;
  b.components = g.components;
  const size_t row = size_t(3) * g.frames;
  b.mean.resize(row);
  for (size_t i = 0; i < row; ++i) b.mean[i] = float(g.mean[i]) * g.mean_step;
  b.basis.resize(g.components * row);
  for (uint32_t k = 0; k < g.components; ++k)
    for (size_t i = 0; i < row; ++i) b.basis[k * row + i] = float(g.basis[k * row + i]) * g.basis_step[k];
  return b;
}

void GroupFrames::reset(const TrajectoryGroup& g, const CodingOrder& order, SimdPath path) {
  path_ = path;
  basis_ = dequantisedBasis(g);
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
        panel[size_t(k) * kLanes] = dequantisedCoefficient(c[k], g.coefficient_step);
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

bool GroupFrames::frame(uint32_t t, float* xyz) const {
  if (batch_first_ == UINT32_MAX || t >= batch_first_ + kBatch) {
    computeBatch(t);
  } else if (t < batch_first_) {  // going backwards: the batch ends at t, for the frames before it
    computeBatch(t >= kBatch - 1 ? t - (kBatch - 1) : 0);
  }
  const size_t size = size_t(3) * vertices_;
  copyOnThreads(&batch_[(t - batch_first_) * size], size, xyz);
  return ((batch_damaged_ >> (t - batch_first_)) & 1) == 0;
}

}  // namespace animc
