// SPDX-License-Identifier: Apache-2.0
#include "metrics/compare_sequences.h"

namespace animc {

Result<SequenceMetrics> compareSequences(FrameSource& original, FrameSource& reconstructed,
                                         const ProgressFn& progress, PerFrameErrors per_frame) {
  const uint32_t n = original.topology().vertex_count;
  if (reconstructed.topology().vertex_count != n)
    return badInput(reconstructed.where() + ": " + std::to_string(reconstructed.topology().vertex_count) +
                    " vertices, the original has " + std::to_string(n));
  const int64_t frames = original.frameCount();
  MetricsAccumulator metrics(n, per_frame);
  std::vector<float> a, b;
  for (;;) {
    ANIMC_ASSIGN_OR_RETURN(bool more_a, original.next(a));
    ANIMC_ASSIGN_OR_RETURN(bool more_b, reconstructed.next(b));
    if (more_a != more_b)
      return badInput(std::string(more_a ? "the reconstruction" : "the original") + " has fewer frames (" +
                      std::to_string(metrics.frames()) + ")");
    if (!more_a) break;
    metrics.addFrame(a.data(), b.data());
    if (progress && frames > 0 && !progress(int(100 * metrics.frames() / frames), "measuring errors"))
      return cancelled();
  }
  return metrics.finish();
}

}  // namespace animc
