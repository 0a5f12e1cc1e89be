// SPDX-License-Identifier: Apache-2.0
// The figures every subcommand prints, text or JSON, from the library's one metrics module.
#pragma once
#include <string>

#include "api.h"
#include "metrics/json_writer.h"
#include "metrics/sequence_metrics.h"

namespace animc::cli {

// A JSON report that starts with "animc_version", so that saved figures say what made them.
JsonObject newReport();
void addSettings(JsonObject& o, const EncodeSettings& s);
void addSizes(JsonObject& o, uint64_t file_bytes, uint64_t static_bytes, uint32_t vertices, int64_t frames);
void addMetrics(JsonObject& o, const SequenceMetrics& m, bool per_frame);

}  // namespace animc::cli
