// SPDX-License-Identifier: Apache-2.0
#include "report/encode_metrics.h"

#include <vector>

namespace animc {

FrameObserver measuringObserver(MetricsAccumulator& metrics, FloatFrameObserver then, VertexErrorFn each_vertex) {
  // The encoder reconstructs in double; measure what the decoder outputs, 32-bit floats.
  std::vector<float> reconstruction;
  return [&metrics, then = std::move(then), each_vertex = std::move(each_vertex), reconstruction](
             int64_t frame, const float* original, const std::vector<double>& reconstructed) mutable {
    reconstruction.assign(reconstructed.begin(), reconstructed.end());
    metrics.addFrame(original, reconstruction.data(), each_vertex);
    if (then) then(frame, original, reconstruction.data());
  };
}

}  // namespace animc
