// SPDX-License-Identifier: Apache-2.0
#include "report/report.h"

#include <cstdio>

#include "animc/animc.h"

namespace animc {
namespace {

constexpr int kTextDigits = 6;  // enough for a log line; JSON keeps kJsonDigits

}  // namespace

std::string describeSettings(const EncodeSettings& s) {
  return "codec: " + std::string(s.entry().name) + ", " + s.entry().describe(s.options) + ", iframe interval " +
         std::to_string(s.iframe_interval) + "\n";
}

std::string formatSizeText(uint64_t file_bytes, uint64_t static_bytes, uint32_t vertices, int64_t frames) {
  const SizeFigures f = sizeFigures(file_bytes, static_bytes, vertices, frames);
  char line[256];
  std::snprintf(line, sizeof line, "size: %llu bytes, ratio %.2f:1, %.4f bits/vertex/frame (motion only %.4f)\n",
                (unsigned long long)file_bytes, f.ratio, f.bpvf, f.motion_bpvf);
  return line;
}

std::string formatMetricsText(const SequenceMetrics& m) {
  std::string out;
  auto line = [&out](const char* name, const std::string& value, const char* unit) {
    out += name;
    out += ": ";
    out += value;
    out += unit;
    out += '\n';
  };
  auto number = [](double v) { return formatDouble(v, kTextDigits); };
  line("frames", std::to_string(m.frames), "");
  line("vertices", std::to_string(m.vertices), "");
  line("kg_error", number(m.kg_error), " %");
  line("psnr", number(m.psnr), " dB");
  line("max_error", number(m.max_error), "");
  line("max_error_rel_diag", number(m.max_error_rel_diag), "");
  line("max_error_rel_cube", number(m.max_error_rel_cube), "");
  line("rms_error", number(m.rms_error), "");
  line("rms_error_rel_diag", number(m.rms_error_rel_diag), "");
  line("bbox_diagonal", number(m.bbox_diagonal), "");
  return out;
}

std::string formatStedText(const StedFigures& f) {
  return "sted: " + formatDouble(f.sted, kTextDigits) + " (spatial " + formatDouble(f.spatial, kTextDigits) +
         ", temporal " + formatDouble(f.temporal, kTextDigits) + ")\n";
}

double encodeMvps(const EncodeSummary& report) {
  if (!(report.encode_seconds > 0)) return 0;
  return double(report.vertices) * double(report.frames) / report.encode_seconds / 1e6;
}

std::string formatEncodeResult(const EncodeSettings& settings, const EncodeSummary& report) {
  return describeSettings(settings) +
         formatSizeText(report.bytes, report.static_bytes, report.vertices, report.frames);
}

std::string formatEncodeSummary(const EncodeSettings& settings, const EncodeSummary& report,
                                const SequenceMetrics& metrics, const std::string& time_note) {
  char time[96];
  std::snprintf(time, sizeof time, "encode time: %.3f s (%.2f M vertices/s)", report.encode_seconds,
                encodeMvps(report));
  return formatEncodeResult(settings, report) + formatMetricsText(metrics) + time + time_note + "\n";
}

JsonObject newReport() {
  JsonObject o;
  o.add("animc_version", animcVersion());
  return o;
}

void addSettings(JsonObject& o, const EncodeSettings& s) {
  o.add("codec", s.entry().name);
  for (const SettingValue& setting : s.entry().settings(s.options))
    std::visit([&](const auto& value) { o.add(setting.key, value); }, setting.value);
  o.add("iframe_interval", s.iframe_interval);
}

void addSizes(JsonObject& o, uint64_t file_bytes, uint64_t static_bytes, uint32_t vertices, int64_t frames) {
  const SizeFigures f = sizeFigures(file_bytes, static_bytes, vertices, frames);
  o.add("file_bytes", file_bytes);
  o.add("static_bytes", static_bytes);
  o.add("ratio", f.ratio);
  o.add("bpvf", f.bpvf);
  o.add("motion_bpvf", f.motion_bpvf);
}

void addMetrics(JsonObject& o, const SequenceMetrics& m, bool per_frame) {
  o.add("frames", m.frames);
  o.add("vertices", m.vertices);
  o.add("kg_error", m.kg_error);
  o.add("psnr", m.psnr);
  o.add("max_error", m.max_error);
  o.add("max_error_rel_diag", m.max_error_rel_diag);
  o.add("max_error_rel_cube", m.max_error_rel_cube);
  o.add("rms_error", m.rms_error);
  o.add("rms_error_rel_diag", m.rms_error_rel_diag);
  o.add("bbox_diagonal", m.bbox_diagonal);
  if (!per_frame) return;
  std::vector<double> rms, max;
  rms.reserve(m.per_frame.size());
  max.reserve(m.per_frame.size());
  for (const FrameError& e : m.per_frame) {
    rms.push_back(e.rms);
    max.push_back(e.max);
  }
  o.add("per_frame_rms", rms);
  o.add("per_frame_max", max);
}

void addSted(JsonObject& o, const StedFigures& f) {
  o.add("sted", f.sted);
  o.add("sted_spatial", f.spatial);
  o.add("sted_temporal", f.temporal);
}

}  // namespace animc
