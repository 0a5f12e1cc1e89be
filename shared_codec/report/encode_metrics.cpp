// SPDX-License-Identifier: Apache-2.0
#include "report/encode_metrics.h"

namespace animc {

FrameObserver measuringObserver(MetricsAccumulator& metrics, FrameObserver then, VertexErrorFn each_vertex) {
  return [&metrics, then = std::move(then), each_vertex = std::move(each_vertex)](
             int64_t frame, const float* original, const float* reconstructed) {
    metrics.addFrame(original, reconstructed, each_vertex);
    if (then) then(frame, original, reconstructed);
  };
}

}  // namespace animc
