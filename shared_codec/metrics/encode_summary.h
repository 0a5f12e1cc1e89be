// SPDX-License-Identifier: Apache-2.0
// The text an encode ends with, worded the same in `animc encode`, MeshLab's Compress filter
// and the .ams save plugin: the settings, the size, the error metrics and the speed.
#pragma once
#include <string>

#include "api.h"
#include "metrics/sequence_metrics.h"

namespace animc {

// Millions of vertex positions encoded per second. 0 when the encode took no measurable time:
// a speed computed from a zero (or clamped) time would be meaningless.
double encodeMvps(const EncodeReport& report);

// What was written: the settings line (describeSettings) and the size line (formatSizeText).
std::string formatEncodeResult(const EncodeSettings& settings, const EncodeReport& report);

// formatEncodeResult, the error metrics (formatMetricsText), then the line
// "encode time: S s (M M vertices/s)" with time_note appended to it. Every line ends in '\n'.
std::string formatEncodeSummary(const EncodeSettings& settings, const EncodeReport& report,
                                const SequenceMetrics& metrics, const std::string& time_note = "");

}  // namespace animc
