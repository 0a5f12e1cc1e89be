// SPDX-License-Identifier: Apache-2.0
// The project's only implementation of its quality and size figures (CLI, MeshLab plugins and
// benchmarks all call it, so published numbers agree). Definitions follow the literature and
// match seqmetrics.py of the shared tools beside the repository, the independent numpy
// cross-check (tests/cli/metrics_crosscheck.sh). Text and JSON of these figures: report/.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace animc {

struct FrameError {
  double rms = 0;  // sqrt(mean over the frame's vertices of |v' - v|^2), absolute
  double max = 0;  // max over the frame's vertices of |v' - v|, absolute
};

struct SequenceMetrics {
  int64_t frames = 0;
  uint32_t vertices = 0;
  // Karni-Gotsman, percent: 100 * ||A - A'||_F / ||A - E(A)||_F, E(A) = per-frame centroid of
  // the original replicated over its vertices.
  double kg_error = 0;
  // 10 * log10(dmax^2 / AVGMSE), dmax = bbox_diagonal, AVGMSE = mean over all vertices of all
  // frames of |v' - v|^2. +inf when exact (written null in JSON).
  double psnr = 0;
  double max_error = 0;           // max Euclidean vertex error, absolute
  double max_error_rel_diag = 0;  // max_error / dmax
  // Max over frames f of (max vertex error in f) / S_f, S_f = max(largest bbox side of
  // original frame f, of original frame f-1): the Affine-Octree paper's ME scale, since the
  // codec's cube for frame f may come from frame f-1.
  double max_error_rel_cube = 0;
  double rms_error = 0;           // sqrt(AVGMSE)
  double rms_error_rel_diag = 0;  // rms_error / dmax
  double bbox_diagonal = 0;       // dmax: diagonal of the bbox of the whole original sequence
  std::vector<FrameError> per_frame;
};

using VertexErrorFn = std::function<void(uint32_t vertex, double error)>;

// Whether the per-frame errors (SequenceMetrics::per_frame, 16 bytes a frame) are kept: an
// encode or a comparison that reports only the totals drops them, so that its memory does not
// grow with the frame count.
enum class PerFrameErrors { kKeep, kDrop };

// Streams frames one at a time; memory is O(frames) for per_frame only (kKeep), never
// O(N * frames).
// Degenerate scales (an all-coincident original, so dmax, S_f or the KG denominator is 0) give
// a relative figure of 0 when the error is 0 too, else +inf. An empty sequence reads as exact.
// A NaN in a reconstruction propagates to every figure it touches rather than being hidden.
class MetricsAccumulator {
 public:
  explicit MetricsAccumulator(uint32_t vertex_count, PerFrameErrors per_frame = PerFrameErrors::kKeep);

  // original and reconstructed: 3 * vertex_count floats each (x y z per vertex), non-null
  // unless vertex_count is 0. The original should be finite (the readers reject NaN).
  // each_vertex, when given, is called with every vertex's error |v' - v| (what MeshLab's
  // filters colour the vertices by).
  void addFrame(const float* original, const float* reconstructed, const VertexErrorFn& each_vertex = {});

  // The figures so far; may be called repeatedly, frames can still be added afterwards.
  SequenceMetrics finish() const;

  int64_t frames() const { return frames_; }

 private:
  uint32_t vertex_count_;
  int64_t frames_ = 0;
  double sum_sq_error_ = 0;     // sum over all vertices of all frames of |v' - v|^2
  double sum_sq_centred_ = 0;   // sum of |v - centroid of its frame|^2 (the KG denominator)
  double max_error_ = 0;
  double max_error_rel_cube_ = 0;
  double previous_side_ = 0;    // largest bbox side of the previous original frame
  std::array<double, 3> sequence_min_;
  std::array<double, 3> sequence_max_;
  PerFrameErrors keep_;
  std::vector<FrameError> per_frame_;
};

struct SizeFigures {
  double ratio = 0;        // 12 * N * F / file_bytes: raw size as 32-bit floats over file size
  double bpvf = 0;         // 8 * file_bytes / (N * F)
  double motion_bpvf = 0;  // 8 * (file_bytes - static_bytes) / (N * F)
};

// static_bytes: what the file spends on the connectivity and the first frame. Plain IEEE
// division: a zero denominator yields inf (or NaN for 0/0), which JSON writes as null.
SizeFigures sizeFigures(uint64_t file_bytes, uint64_t static_bytes, uint32_t vertices,
                        int64_t frames);

}  // namespace animc
