// SPDX-License-Identifier: Apache-2.0
#include "metrics/encode_summary.h"

#include <cstdio>

namespace animc {

double encodeMvps(const EncodeReport& report) {
  if (!(report.encode_seconds > 0)) return 0;
  return double(report.vertices) * double(report.frames) / report.encode_seconds / 1e6;
}

std::string formatEncodeResult(const EncodeSettings& settings, const EncodeReport& report) {
  return describeSettings(settings) +
         formatSizeText(report.file_bytes, report.static_bytes, report.vertices, report.frames);
}

std::string formatEncodeSummary(const EncodeSettings& settings, const EncodeReport& report,
                                const SequenceMetrics& metrics, const std::string& time_note) {
  char time[96];
  std::snprintf(time, sizeof time, "encode time: %.3f s (%.2f M vertices/s)", report.encode_seconds,
                encodeMvps(report));
  return formatEncodeResult(settings, report) + formatMetricsText(metrics) + time + time_note + "\n";
}

}  // namespace animc
