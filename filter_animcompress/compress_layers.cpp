// SPDX-License-Identifier: GPL-3.0-or-later
#include "compress_layers.h"

#include <QFileInfo>
#include <chrono>
#include <cstdio>

#include "api.h"
#include "encode_parameters.h"
#include "error_colouring.h"
#include "layer_frames.h"
#include "report/encode_metrics.h"
#include "report/report.h"
#include "animc/animc.h"

namespace animc::meshlab {
namespace {

// What the encoder observer builds while it runs: the metrics, the layers it added, and the
// errors of the original layers when they are the ones to colour. It leaves the originals
// alone: the encode may still fail on a later frame, and then they must stay as they were.
struct CompressOutput {
  explicit CompressOutput(uint32_t vertices) : metrics(vertices, PerFrameErrors::kDrop) {}
  MetricsAccumulator metrics;
  QList<MeshModel*> decoded_layers;
  std::vector<std::vector<Scalarm>> original_errors;  // one per frame
};

// After a successful encode: every shown layer gets its errors as quality and colours on the
// scale of the whole animation.
void colourByError(const CompressOutput& out, const QList<MeshModel*>& originals, float scale_max) {
  for (size_t i = 0; i < out.original_errors.size(); ++i) storeQuality(*originals[int(i)], out.original_errors[i]);
  for (MeshModel* shown : out.decoded_layers.isEmpty() ? originals : out.decoded_layers)
    colourByQuality(*shown, scale_max);
}

}  // namespace

void addCompressParameters(const MeshDocument& md, RichParameterList& par) {
  addEncodeParameters(par);
  const QList<MeshModel*> all = compat::layers(md);
  QString dir = all.isEmpty() ? QString() : QFileInfo(all[0]->fullName()).absolutePath();
  const QString default_path = dir.isEmpty() ? QString("animation.ams") : dir + "/animation.ams";
  par.addParam(RichBool("VisibleOnly", false, "Visible layers only",
                        "Use only the visible layers as frames (in document order); otherwise all layers."));
  par.addParam(compat::RichSaveFile("OutputFile", default_path, "*.ams", "Output .ams file",
                            "Where the compressed animation is written (atomically: nothing appears on failure)."));
  par.addParam(RichBool("AddReconstructed", true, "Add reconstructed layers",
                        "Add one layer per frame holding what a decoder of the file will produce."));
  par.addParam(RichBool("ColourByError", true, "Colour by error",
                        "Store each vertex's reconstruction error as vertex quality and colour it, blue = 0 "
                        "to red = the largest error of the whole animation; on the reconstructed layers, "
                        "or on the originals when no reconstructed layers are added."));
}

std::string compressLayers(MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb,
                           const LogFn& log, CompressFigures* figures) {
  const auto started = std::chrono::steady_clock::now();
  const QList<MeshModel*> layers = frameLayers(md, par.getBool("VisibleOnly"));
  if (layers.size() < 2)
    return "an animation needs at least 2 layers (frames); found " + std::to_string(layers.size());
  Result<EncodeSettings> settings = encodeSettingsFrom(par);
  if (!settings.ok()) return settings.status().message();
  const std::string path = par.getSaveFileName("OutputFile").toStdString();
  if (path.empty()) return "no output file given";
  Result<std::unique_ptr<LayerFrameSource>> source = LayerFrameSource::create(&md, layers);
  if (!source.ok()) return source.status().message();
  const Topology& topology = source.value()->topology();

  const bool add_decoded = par.getBool("AddReconstructed");
  const bool colour = par.getBool("ColourByError");
  CompressOutput out(topology.vertex_count);
  std::vector<Scalarm> frame_errors(topology.vertex_count);  // of the frame being shown
  auto collect = [&](uint32_t vertex, double error) { frame_errors[vertex] = Scalarm(error); };
  auto show = [&](int64_t frame, const float*, const float* reconstruction) {
    if (add_decoded) {
      MeshModel* decoded = md.addNewMesh("", "decoded " + layers[int(frame)]->label(), false);
      fillMesh(*decoded, topology, reconstruction);
      out.decoded_layers << decoded;
      if (colour) storeQuality(*decoded, frame_errors);
    } else if (colour) {
      out.original_errors.push_back(frame_errors);
    }
  };
  Result<EncodeSummary> report = encodeSequence(*source.value(), settings.value(), path, progressFrom(cb),
                                               measuringObserver(out.metrics, show, collect));
  if (!report.ok()) {
    for (MeshModel* m : out.decoded_layers) compat::removeLayer(md, m);
    return report.status().message();
  }

  const SequenceMetrics m = out.metrics.finish();
  if (colour) colourByError(out, layers, float(m.max_error));
  const EncodeSummary& r = report.value();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  log("Compressed " + std::to_string(r.frames) + " frames of " + std::to_string(r.vertices) +
      " vertices (" + std::to_string(r.triangles) + " triangles) into " + path + " (animcompress " +
      animcVersion() + ")");
  char whole_filter[64];
  std::snprintf(whole_filter, sizeof whole_filter, "; whole filter %.3f s", seconds);
  logLines(log, formatEncodeSummary(settings.value(), r, m, whole_filter));
  if (add_decoded) log("added " + std::to_string(out.decoded_layers.size()) + " reconstructed layers ('decoded ...')");
  if (figures != nullptr) {
    const SizeFigures size = sizeFigures(r.bytes, r.static_bytes, r.vertices, r.frames);
    *figures = {size.ratio, size.bpvf, m.kg_error, m.psnr, m.max_error, r.bytes};
  }
  return {};
}

}  // namespace animc::meshlab
