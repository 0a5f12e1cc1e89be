// SPDX-License-Identifier: Apache-2.0
#include "report.h"

#include "version.h"

namespace animc::cli {

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
  o.add("max_error_rel_cube", m.max_error_rel_cube);
  o.add("max_error_rel_diag", m.max_error_rel_diag);
  o.add("rms_error", m.rms_error);
  o.add("rms_error_rel_diag", m.rms_error_rel_diag);
  o.add("bbox_diagonal", m.bbox_diagonal);
  if (!per_frame) return;
  std::vector<double> rms, max;
  for (const FrameError& e : m.per_frame) {
    rms.push_back(e.rms);
    max.push_back(e.max);
  }
  o.add("per_frame_rms", rms);
  o.add("per_frame_max", max);
}

}  // namespace animc::cli
