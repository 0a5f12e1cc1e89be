// SPDX-License-Identifier: GPL-3.0-or-later
#include "io_animstream.h"

#include <common/mlexception.h>

#include "animc/animc.h"
#include "encode_parameters.h"
#include "frame_range_parameters.h"
#include "layer_frames.h"
#include "plugin_support.h"
#include "report/report.h"

using namespace animc::meshlab;

namespace {

[[noreturn]] void fail(const QString& what, const QString& fileName, const std::string& why) {
  throw MLException("Cannot " + what + " " + fileName + ": " + QString::fromStdString(why));
}

// Runs body; whatever it lets out other than MLException becomes one, as MeshLab expects.
template <typename Body>
void guarded(const QString& what, const QString& fileName, Body body) {
  try {
    body();
  } catch (const MLException&) {
    throw;
  } catch (...) {
    fail(what, fileName, currentExceptionMessage());
  }
}

}  // namespace

QString IoAnimStreamPlugin::vendor() const { return "animcompress " ANIMC_VERSION_STRING; }

std::list<FileFormat> IoAnimStreamPlugin::importFormats() const {
  return {FileFormat("animcompress animation", tr("AMS"))};
}

// A mesh save sees one layer only: a one-frame animation is no use, so .ams is a project format.
std::list<FileFormat> IoAnimStreamPlugin::exportFormats() const { return {}; }

std::list<FileFormat> IoAnimStreamPlugin::exportProjectFormats() const {
  return {FileFormat("animcompress animation (every layer a frame)", tr("AMS"))};
}

void IoAnimStreamPlugin::exportMaskCapability(const QString&, int& capability, int& defaultBits) const {
  capability = 0;  // positions and triangles only: no colours, normals or texture coordinates
  defaultBits = 0;
}

RichParameterList IoAnimStreamPlugin::initPreOpenParameter(const QString&) const {
  RichParameterList par;
  addFrameRangeParameters(par);
  addLimitParameters(par);
  return par;
}

unsigned int IoAnimStreamPlugin::numberMeshesContainedInFile(const QString&, const QString& fileName,
                                                             const RichParameterList& par) const {
  // A bad file or range is refused here, before MeshLab makes any layer.
  unsigned count = 0;
  guarded("open", fileName, [&] {
    const auto frames = amsFrameCount(fileName.toStdString(), frameRangeFrom(par));
    if (!frames.ok()) fail("open", fileName, frames.status().message());
    count = unsigned(frames.value());
  });
  return count;
}

void IoAnimStreamPlugin::open(const QString&, const QString& fileName, const std::list<MeshModel*>& layers,
                              std::list<int>& masks, const RichParameterList& par, vcg::CallBackPos* cb) {
  guarded("open", fileName, [&] { openLayers(fileName, QList<MeshModel*>(layers.begin(), layers.end()), par, cb); });
  masks.assign(layers.size(), 0);
}

// Only reached when a caller opens into one layer: the range's first frame.
void IoAnimStreamPlugin::open(const QString&, const QString& fileName, MeshModel& m, int& mask,
                              const RichParameterList& par, vcg::CallBackPos* cb) {
  RichParameterList one = par;
  if (one.hasParameter("LastFrame")) one.setValue("LastFrame", IntValue(frameRangeFrom(par).first_frame));
  guarded("open", fileName, [&] { openLayers(fileName, {&m}, one, cb); });
  mask = 0;
}

void IoAnimStreamPlugin::openLayers(const QString& fileName, const QList<MeshModel*>& layers,
                                    const RichParameterList& par, vcg::CallBackPos* cb) {
  const AmsImport range = frameRangeFrom(par);
  const animc::Status s = importAmsInto(fileName.toStdString(), range, layers, progressFrom(cb));
  if (!s.ok()) fail("open", fileName, s.message());
  if (cb != nullptr) cb(100, "");  // the GUI would keep showing "decoding frames" otherwise
  log("Opened %s: frames %lld to %lld as %d layers of %d vertices", qUtf8Printable(fileName),
      (long long)range.first_frame, (long long)(range.first_frame + layers.size() - 1), int(layers.size()),
      layers.isEmpty() ? 0 : layers[0]->cm.vn);
}

void IoAnimStreamPlugin::save(const QString& format, const QString&, MeshModel&, const int,
                              const RichParameterList&, vcg::CallBackPos*) {
  wrongSaveFormat(format);
}

void IoAnimStreamPlugin::saveProject(const QString&, const QString& fileName, const MeshDocument& md,
                                     bool onlyVisibleMeshes, const std::vector<MLRenderingData>&,
                                     vcg::CallBackPos* cb) {
  guarded("save", fileName, [&] {
    RichParameterList defaults;
    addEncodeParameters(defaults);
    auto settings = encodeSettingsFrom(defaults);
    if (!settings.ok()) fail("save", fileName, settings.status().message());
    auto source = LayerFrameSource::create(&md, frameLayers(md, onlyVisibleMeshes));
    if (!source.ok()) fail("save", fileName, source.status().message());
    auto report = animc::encodeSequence(*source.value(), settings.value(), fileName.toStdString(), progressFrom(cb));
    if (!report.ok()) fail("save", fileName, report.status().message());
    const animc::EncodeSummary& r = report.value();
    log("Saved %lld layers of %u vertices as frames of %s", (long long)r.frames, r.vertices, qUtf8Printable(fileName));
    logLines([this](const std::string& line) { log(line); }, animc::formatEncodeResult(settings.value(), r));
  });
}

MESHLAB_PLUGIN_NAME_EXPORTER(IoAnimStreamPlugin)
