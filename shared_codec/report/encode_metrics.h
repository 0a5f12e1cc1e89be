// SPDX-License-Identifier: Apache-2.0
// An encode measured while it runs, from the reconstructions the encoder hands its observer,
// so the file is never decoded again: `animc encode` and MeshLab's Compress filter.
#pragma once
#include <cstdint>
#include <functional>

#include "api.h"
#include "metrics/sequence_metrics.h"

namespace animc {

// An observer for encodeSequence that adds every frame to `metrics` (which must outlive it),
// passing each vertex's error to `each_vertex`, then hands the frame to `then` (each when given).
FrameObserver measuringObserver(MetricsAccumulator& metrics, FrameObserver then = {},
                                VertexErrorFn each_vertex = {});

}  // namespace animc
