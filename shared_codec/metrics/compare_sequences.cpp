// SPDX-License-Identifier: Apache-2.0
#include "metrics/compare_sequences.h"

#include <optional>

namespace animc {

static_assert(sizeof(Triangle) == 3 * sizeof(uint32_t), "triangles are read as a flat index array");

Result<SequenceMetrics> compareSequences(FrameSource& original, FrameSource& reconstructed,
                                         const ProgressFn& progress, PerFrameErrors per_frame,
                                         StedFigures* sted) {
  const uint32_t n = original.topology().vertex_count;
  if (reconstructed.topology().vertex_count != n)
    return badInput(reconstructed.where() + ": " + std::to_string(reconstructed.topology().vertex_count) +
                    " vertices, the original has " + std::to_string(n));
  const int64_t frames = original.frameCount();
  MetricsAccumulator metrics(n, per_frame);
  const std::vector<Triangle>& triangles = original.topology().triangles;
  std::optional<StedAccumulator> perceptual;
  if (sted) perceptual.emplace(n, triangles.empty() ? nullptr : triangles[0].data(), triangles.size());
  std::vector<float> a, b;
  for (;;) {
    ANIMC_ASSIGN_OR_RETURN(bool more_a, original.next(a));
    ANIMC_ASSIGN_OR_RETURN(bool more_b, reconstructed.next(b));
    if (more_a != more_b)
      return badInput(std::string(more_a ? "the reconstruction" : "the original") + " has fewer frames (" +
                      std::to_string(metrics.frames()) + ")");
    if (!more_a) break;
    metrics.addFrame(a.data(), b.data());
    if (perceptual) perceptual->addFrame(a.data(), b.data());
    if (progress && frames > 0 && !progress(int(100 * metrics.frames() / frames), "measuring errors"))
      return cancelled();
  }
  if (perceptual) *sted = perceptual->finish();
  return metrics.finish();
}

}  // namespace animc
