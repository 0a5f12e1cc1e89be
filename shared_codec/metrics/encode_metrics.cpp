// SPDX-License-Identifier: Apache-2.0
#include "metrics/encode_metrics.h"

#include <vector>

namespace animc {

FrameObserver measuringObserver(MetricsAccumulator& metrics, FloatFrameObserver then) {
  // The encoder reconstructs in double; measure what the decoder outputs, 32-bit floats.
  std::vector<float> reconstruction;
  return [&metrics, then = std::move(then), reconstruction](int64_t frame, const float* original,
                                                            const std::vector<double>& reconstructed) mutable {
    reconstruction.assign(reconstructed.begin(), reconstructed.end());
    metrics.addFrame(original, reconstruction.data());
    if (then) then(frame, original, reconstruction.data());
  };
}

}  // namespace animc
