// SPDX-License-Identifier: Apache-2.0
// Every figure as people read it, in one place above the API: the settings, sizes and error
// metrics as text lines (animc's output, MeshLab's log) and as JSON members (`animc ... --json`),
// so the CLI, the plugins and the benchmarks word and key them alike.
#pragma once
#include <string>

#include "api.h"
#include "metrics/sequence_metrics.h"
#include "report/json_writer.h"

namespace animc {

// --- text --------------------------------------------------------------------------------

// One line such as "codec: affine-octree, profile predictive, max error 0.01 of the root cube,
// bits 16, iframe interval 0", naming the settings of the chosen codec only.
std::string describeSettings(const EncodeSettings& s);

// One line: "size: B bytes, ratio R:1, X bits/vertex/frame (motion only Y)".
std::string formatSizeText(uint64_t file_bytes, uint64_t static_bytes, uint32_t vertices, int64_t frames);

// One "name: value" line per figure (names as in the JSON, units after the value). Per-frame
// values are not listed.
std::string formatMetricsText(const SequenceMetrics& m);

// "sted: X (spatial S, temporal T)", the StedOptions used said in docs/metrics.md.
std::string formatStedText(const StedFigures& f);

// Millions of vertex positions encoded per second. 0 when the encode took no measurable time:
// a speed computed from a zero (or clamped) time would be meaningless.
double encodeMvps(const EncodeSummary& report);

// What was written: describeSettings, then formatSizeText.
std::string formatEncodeResult(const EncodeSettings& settings, const EncodeSummary& report);

// formatEncodeResult, formatMetricsText, then "encode time: S s (M M vertices/s)" with
// time_note appended: the text an encode ends with in animc and in MeshLab's log.
std::string formatEncodeSummary(const EncodeSettings& settings, const EncodeSummary& report,
                                const SequenceMetrics& metrics, const std::string& time_note = "");

// Every line above ends in '\n'.

// --- JSON --------------------------------------------------------------------------------

// A JSON report that starts with "animc_version", so that saved figures say what made them.
JsonObject newReport();
// "codec", the codec's settings (CodecEntry::settings) and "iframe_interval".
void addSettings(JsonObject& o, const EncodeSettings& s);
// file_bytes, static_bytes, ratio, bpvf, motion_bpvf.
void addSizes(JsonObject& o, uint64_t file_bytes, uint64_t static_bytes, uint32_t vertices, int64_t frames);
// frames, vertices, kg_error, psnr, max_error, max_error_rel_diag, max_error_rel_cube,
// rms_error, rms_error_rel_diag, bbox_diagonal and, with per_frame, the arrays per_frame_rms
// and per_frame_max. inf and NaN are written as null.
void addMetrics(JsonObject& o, const SequenceMetrics& m, bool per_frame);
// sted, sted_spatial, sted_temporal.
void addSted(JsonObject& o, const StedFigures& f);

}  // namespace animc
