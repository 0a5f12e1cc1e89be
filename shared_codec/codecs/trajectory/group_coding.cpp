// SPDX-License-Identifier: Apache-2.0
#include "codecs/trajectory/group_coding.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <thread>

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

// The values of a row, each handed to store(index in the row, value) as it is decoded.
template <class Store>
bool decodeRow(RangeDecoder& rc, RawBitReader& raw, ClassedIntegerModel& m, uint32_t frames, Store store) {
  for (uint32_t c = 0; c < 3; ++c) {
    int64_t previous = 0;
    for (uint32_t t = 0; t < frames; ++t) {
      const int64_t v = previous + decodeClassed(rc, raw, m);
      if (!fitsInt32(v)) return false;
      store(c * frames + t, int32_t(v));
      previous = v;
    }
  }
  return true;
}

// The mean and the basis vectors (K rows of 3G) of a group into `mean` and `basis`, each
// value as convert(value, its row's step) makes it.
template <class Value, class Convert>
bool decodeRows(RangeDecoder& rc, RawBitReader& raw, GroupModels& models, const TrajectoryGroup& g, Value* mean,
                Value* basis, Convert convert) {
  auto into = [&](Value* out, float step) { return [=](uint32_t i, int32_t v) { out[i] = convert(v, step); }; };
  bool fits = decodeRow(rc, raw, models.mean, g.frames, into(mean, g.mean_step));
  const size_t row = size_t(3) * g.frames;
  for (uint32_t k = 0; fits && k < g.components; ++k)
    fits = decodeRow(rc, raw, models.basis[coefficientBand(k)], g.frames, into(basis + k * row, g.basis_step[k]));
  return fits;
}

bool usableStep(float s) { return std::isfinite(s) && s > 0; }

// Positions a walk does between two reports of its progress.
constexpr uint32_t kPositionsPerStep = 1024;

// Waits until a walk has done `wanted` positions; returns how many it has done.
uint32_t awaitPositions(const std::atomic<uint32_t>& done, uint32_t wanted) {
  uint32_t now;
  while ((now = done.load(std::memory_order_acquire)) < wanted) std::this_thread::yield();
  return now;
}

}  // namespace

CodingOrder::CodingOrder(const Topology& topology) {
  const VertexAdjacency adjacency(topology);
  *this = CodingOrder(adjacency);
  walk(adjacency, nullptr);
}

// Each edge is listed once, from its later end: `earlier` is exactly half the adjacency's
// entries, whose rows are symmetric and hold no vertex itself (core/adjacency.h).
CodingOrder::CodingOrder(const VertexAdjacency& adjacency)
    : vertex(adjacency.vertices()), first(size_t(adjacency.vertices()) + 1), earlier(adjacency.entries() / 2),
      position_(adjacency.vertices(), UINT32_MAX) {}

void CodingOrder::walk(const VertexAdjacency& adjacency, std::atomic<uint32_t>* done) {
  const uint32_t n = adjacency.vertices();
  uint32_t* const position = position_.data();
  uint32_t placed = 0, listed = 0;
  first[0] = 0;
  // The vertices placed so far are the breadth-first queue: those from `next` on are waiting.
  // When one leaves it, every vertex before it has its position, and those of its neighbours
  // are its earlier ones: they are listed then, while its row of neighbours is at hand.
  auto place = [&](uint32_t v) {
    position[v] = placed;
    vertex[placed++] = v;
  };
  for (uint32_t root = 0; root < n; ++root) {
    if (position[root] != UINT32_MAX) continue;
    place(root);
    for (uint32_t next = placed - 1; next < placed; ++next) {
      for (const uint32_t* w = adjacency.begin(vertex[next]); w != adjacency.end(vertex[next]); ++w) {
        if (position[*w] == UINT32_MAX) place(*w);
        else if (position[*w] < next)
          earlier[listed++] = position[*w];
      }
      first[next + 1] = listed;
      // A reader following the walk is told in steps: a store per position would cost more
      // than the reader gains.
      if (done && (next + 1) % kPositionsPerStep == 0) done->store(next + 1, std::memory_order_release);
    }
  }
  UninitialisedVector<uint32_t>().swap(position_);  // freed: assigning {} would keep the memory
  if (done) done->store(n, std::memory_order_release);
}

void writeTrajectoryGroup(const TrajectoryGroup& g, const CodingOrder& order, std::vector<uint8_t>& out) {
  out.push_back(kTrajectoryGroupFrame);
  writeTrajectoryGroupFields(g, order, out);
}

void writeTrajectoryGroupFields(const TrajectoryGroup& g, const CodingOrder& order, std::vector<uint8_t>& out) {
  ByteWriter head;
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

Status multiplyAddsAboveLimit(const std::string& what, uint64_t work, uint64_t limit) {
  return limitExceeded(what + " costs " + std::to_string(work) + " multiply-adds, above the limit of " +
                       std::to_string(limit) +
                       "; raise it for a trusted file (DecoderLimits::max_multiply_adds, animc --max-multiply-adds)");
}

Status readTrajectoryGroup(ByteReader payload, const CodingOrder& order, uint64_t max_multiply_adds, TrajectoryGroup& g,
                           GroupBasis* basis, const std::atomic<uint32_t>* done) {
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
    return multiplyAddsAboveLimit("trajectory group of " + std::to_string(components) + " components, " +
                                      std::to_string(n) + " vertices and " + std::to_string(frames) + " frames",
                                  work, max_multiply_adds);
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
  g.coefficients.resize(n * components);
  auto models = std::make_unique<GroupModels>();
  RangeDecoder rc(payload.cursor(), payload.remaining());
  RawBitReader raw(payload.cursor(), payload.remaining());
  bool fits;
  if (basis) {
    basis->frames = frames;
    basis->components = components;
    basis->mean.resize(row);
    basis->basis.resize(components * row);
    g.mean.clear();
    g.basis.clear();
    fits = decodeRows(rc, raw, *models, g, basis->mean.data(), basis->basis.data(),
                      [](int32_t v, float step) { return dequantised(v, step); });
  } else {
    g.mean.resize(row);
    g.basis.resize(components * row);
    fits = decodeRows(rc, raw, *models, g, g.mean.data(), g.basis.data(), [](int32_t v, float) { return v; });
  }
  // Damaged data is found at the end: the loops are as long whatever the bytes, and a
  // decoder that reads past its input gets zeros.
  Predictions predictions(components);
  uint32_t walked = done ? 0 : uint32_t(n);
  for (uint32_t p = 0; fits && p < n; ++p) {
    if (p == walked) walked = awaitPositions(*done, p + 1);
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

Status walkAndReadTrajectoryGroup(const Topology& topology, ByteReader payload, uint64_t max_multiply_adds,
                                  std::unique_ptr<const CodingOrder>& order, TrajectoryGroup& g,
                                  GroupBasis* basis) {
  const VertexAdjacency adjacency(topology);
  auto walking = std::make_unique<CodingOrder>(adjacency);
  std::atomic<uint32_t> done{0};
  Status read;
  runBeside([&] { walking->walk(adjacency, &done); },
            [&] { read = readTrajectoryGroup(payload, *walking, max_multiply_adds, g, basis, &done); });
  order = std::move(walking);
  return read;
}

}  // namespace animc
