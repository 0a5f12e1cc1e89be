// SPDX-License-Identifier: Apache-2.0
#include "metrics/sequence_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>


namespace animc {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// a / b for a relative error a >= 0 over a scale b >= 0. A zero scale with a zero error is
// still an exact result (0), with a positive error infinitely bad; a NaN error stays NaN.
double relativeTo(double a, double b) {
  if (b > 0) return a / b;
  return a == 0 ? 0.0 : a * kInf;
}

// Explicit IEEE semantics without dividing by zero (keeps sanitizer builds quiet).
double divide(double a, double b) {
  if (b != 0) return a / b;
  if (a == 0 || std::isnan(a)) return kNaN;
  return std::copysign(kInf, a);
}

// A NaN, once seen, wins: a broken reconstruction must not report a plausible maximum.
double maxKeepingNaN(double current, double candidate) {
  return (candidate > current || std::isnan(candidate)) ? candidate : current;
}

struct OriginalFrameStats {
  std::array<double, 3> min{kInf, kInf, kInf};
  std::array<double, 3> max{-kInf, -kInf, -kInf};
  double sum_sq_centred = 0;

  double largestSide() const {
    double side = 0;
    for (int c = 0; c < 3; ++c) side = std::max(side, max[c] - min[c]);
    return side;
  }
};

// Bbox and sum of squared distances to the centroid. Two passes (centroid first) rather than
// sum(v^2) - n*c^2, which cancels catastrophically for meshes far from the origin.
OriginalFrameStats measureOriginal(const float* xyz, uint32_t n) {
  OriginalFrameStats stats;
  if (n == 0) return stats;
  std::array<double, 3> sum{0, 0, 0};
  for (size_t i = 0; i < size_t{n} * 3; ++i) {
    const double v = xyz[i];
    const size_t c = i % 3;
    sum[c] += v;
    stats.min[c] = std::min(stats.min[c], v);
    stats.max[c] = std::max(stats.max[c], v);
  }
  std::array<double, 3> centroid{sum[0] / n, sum[1] / n, sum[2] / n};
  for (size_t i = 0; i < size_t{n} * 3; ++i) {
    const double d = xyz[i] - centroid[i % 3];
    stats.sum_sq_centred += d * d;
  }
  return stats;
}

struct FrameErrorSums {
  double sum_sq = 0;
  double max = 0;
};

FrameErrorSums measureError(const float* original, const float* reconstructed, uint32_t n,
                            const VertexErrorFn& each_vertex) {
  FrameErrorSums sums;
  for (uint32_t v = 0; v < n; ++v) {
    const float* a = original + 3 * size_t(v);
    const float* b = reconstructed + 3 * size_t(v);
    const double dx = double{b[0]} - a[0], dy = double{b[1]} - a[1], dz = double{b[2]} - a[2];
    const double sq = dx * dx + dy * dy + dz * dz;
    sums.sum_sq += sq;
    const double error = std::sqrt(sq);
    sums.max = maxKeepingNaN(sums.max, error);
    if (each_vertex) each_vertex(v, error);
  }
  return sums;
}

}  // namespace

MetricsAccumulator::MetricsAccumulator(uint32_t vertex_count, PerFrameErrors per_frame)
    : vertex_count_(vertex_count),
      sequence_min_{kInf, kInf, kInf},
      sequence_max_{-kInf, -kInf, -kInf},
      keep_(per_frame) {}

void MetricsAccumulator::addFrame(const float* original, const float* reconstructed,
                                 const VertexErrorFn& each_vertex) {
  const OriginalFrameStats stats = measureOriginal(original, vertex_count_);
  const FrameErrorSums error = measureError(original, reconstructed, vertex_count_, each_vertex);
  for (int c = 0; c < 3; ++c) {
    sequence_min_[c] = std::min(sequence_min_[c], stats.min[c]);
    sequence_max_[c] = std::max(sequence_max_[c], stats.max[c]);
  }
  sum_sq_error_ += error.sum_sq;
  sum_sq_centred_ += stats.sum_sq_centred;
  max_error_ = maxKeepingNaN(max_error_, error.max);

  // The first frame has no predecessor: previous_side_ starts at 0, so S_0 = its own side.
  const double side = stats.largestSide();
  const double cube_scale = std::max(side, previous_side_);
  max_error_rel_cube_ = maxKeepingNaN(max_error_rel_cube_, relativeTo(error.max, cube_scale));
  previous_side_ = side;

  ++frames_;
  if (keep_ == PerFrameErrors::kDrop) return;
  FrameError frame;
  frame.rms = vertex_count_ > 0 ? std::sqrt(error.sum_sq / vertex_count_) : 0.0;
  frame.max = error.max;
  per_frame_.push_back(frame);
}

SequenceMetrics MetricsAccumulator::finish() const {
  SequenceMetrics m;
  m.frames = frames_;
  m.vertices = vertex_count_;
  const double samples = static_cast<double>(frames_) * vertex_count_;
  const double mse = samples > 0 ? sum_sq_error_ / samples : 0.0;

  double diagonal_sq = 0;
  if (samples > 0) {
    for (int c = 0; c < 3; ++c) {
      const double extent = sequence_max_[c] - sequence_min_[c];
      diagonal_sq += extent * extent;
    }
  }
  m.bbox_diagonal = std::sqrt(diagonal_sq);

  m.kg_error = 100.0 * relativeTo(std::sqrt(sum_sq_error_), std::sqrt(sum_sq_centred_));
  // mse == 0 is exact (+inf); a zero diagonal with an error gives log10(0) = -inf.
  m.psnr = mse == 0 ? kInf : 10.0 * std::log10(diagonal_sq / mse);
  m.max_error = max_error_;
  m.max_error_rel_diag = relativeTo(max_error_, m.bbox_diagonal);
  m.max_error_rel_cube = max_error_rel_cube_;
  m.rms_error = std::sqrt(mse);
  m.rms_error_rel_diag = relativeTo(m.rms_error, m.bbox_diagonal);
  m.per_frame = per_frame_;
  return m;
}

SizeFigures sizeFigures(uint64_t file_bytes, uint64_t static_bytes, uint32_t vertices,
                        int64_t frames) {
  // In double throughout: N * F * 12 overflows nothing, and file - static may be negative
  // (a caller bug that should show, not wrap around).
  const double samples = static_cast<double>(vertices) * static_cast<double>(frames);
  const double bytes = static_cast<double>(file_bytes);
  SizeFigures s;
  s.ratio = divide(12.0 * samples, bytes);
  s.bpvf = divide(8.0 * bytes, samples);
  s.motion_bpvf = divide(8.0 * (bytes - static_cast<double>(static_bytes)), samples);
  return s;
}

}  // namespace animc
