// SPDX-License-Identifier: GPL-3.0-or-later
#include "io_animstream.h"

#include <QFileInfo>

#include "encode_parameters.h"
#include "frame_range_parameters.h"
#include "gui_rendering.h"
#include "layer_frames.h"
#include "report/report.h"
#include "plugin_support.h"

using namespace animc::meshlab;

QList<MeshIOInterface::Format> IoAnimStreamPlugin::importFormats() const {
  return {Format("animcompress animation", tr("AMS"))};
}

QList<MeshIOInterface::Format> IoAnimStreamPlugin::exportFormats() const {
  return {Format("animcompress animation", tr("AMS"))};
}

void IoAnimStreamPlugin::GetExportMaskCapability(QString&, int& capability, int& defaultBits) const {
  capability = 0;  // positions and triangles only: no colours, normals or texture coordinates
  defaultBits = 0;
}

void IoAnimStreamPlugin::initPreOpenParameter(const QString&, const QString&, RichParameterList& par) {
  addFrameRangeParameters(par);
  addLimitParameters(par);
}

void IoAnimStreamPlugin::initSaveParameter(const QString&, MeshModel&, RichParameterList& par) {
  addEncodeParameters(par);
  par.addParam(RichBool("AllLayers", true, "All layers as frames",
                        "Save every layer of the document as one frame, in document order; "
                        "otherwise only this layer (a one-frame animation)."));
}

bool IoAnimStreamPlugin::open(const QString&, const QString& fileName, MeshModel& m, int& mask,
                              const RichParameterList& par, vcg::CallBackPos* cb, QWidget*) {
  try {
    return openFrames(fileName, m, mask, par, cb);
  } catch (...) {
    return fail("open", fileName, currentExceptionMessage());
  }
}

bool IoAnimStreamPlugin::openFrames(const QString& fileName, MeshModel& m, int& mask,
                                    const RichParameterList& par, vcg::CallBackPos* cb) {
  mask = 0;
  AmsImport range = frameRangeFrom(par);
  MeshDocument* md = m.parent;
  if (md == nullptr) range.last_frame = range.first_frame;  // no document to add layers to
  auto layers = importAms(fileName.toStdString(), range, md, &m, progressFrom(cb));
  if (!layers.ok()) return fail("open", fileName, layers.status().message());
  if (md != nullptr) setUpRenderingOfAddedLayers(*md, layers.value().mid(1));
  if (cb != nullptr) cb(100, "");  // the GUI would keep showing "decoding frames" otherwise
  Log("Opened %s: frames %lld to %lld as %d layers of %d vertices", qUtf8Printable(fileName),
      (long long)range.first_frame, (long long)(range.first_frame + layers.value().size() - 1),
      layers.value().size(), m.cm.vn);
  return true;
}

bool IoAnimStreamPlugin::save(const QString&, const QString& fileName, MeshModel& m, const int,
                              const RichParameterList& par, vcg::CallBackPos* cb, QWidget*) {
  try {
    return saveFrames(fileName, m, par, cb);
  } catch (...) {
    return fail("save", fileName, currentExceptionMessage());
  }
}

bool IoAnimStreamPlugin::saveFrames(const QString& fileName, MeshModel& m, const RichParameterList& par,
                                    vcg::CallBackPos* cb) {
  const bool all = !par.hasParameter("AllLayers") || par.getBool("AllLayers");
  const QList<MeshModel*> layers = all && m.parent != nullptr ? frameLayers(*m.parent, false)
                                                              : QList<MeshModel*>{&m};
  RichParameterList defaults;
  addEncodeParameters(defaults);
  auto settings = encodeSettingsFrom(par.hasParameter("Codec") ? par : defaults);
  if (!settings.ok()) return fail("save", fileName, settings.status().message());
  auto source = LayerFrameSource::create(m.parent, layers);
  if (!source.ok()) return fail("save", fileName, source.status().message());
  auto report = animc::encodeSequence(*source.value(), settings.value(), fileName.toStdString(), progressFrom(cb));
  if (!report.ok()) return fail("save", fileName, report.status().message());
  const animc::EncodeSummary& r = report.value();
  Log("Saved %lld layers of %u vertices as frames of %s", (long long)r.frames, r.vertices, qUtf8Printable(fileName));
  const LogFn log = [this](const std::string& line) { Log("%s", line.c_str()); };
  logLines(log, animc::formatEncodeResult(settings.value(), r));
  return true;
}

bool IoAnimStreamPlugin::fail(const QString& what, const QString& fileName, const std::string& why) {
  errorMessage = QString::fromStdString(why);
  Log("Cannot %s %s: %s", qUtf8Printable(what), qUtf8Printable(fileName), why.c_str());
  // meshlabserver neither prints errorMessage nor gives open() a log: say it on stderr too.
  qWarning("io_animstream: cannot %s %s: %s", qUtf8Printable(what), qUtf8Printable(fileName), why.c_str());
  return false;
}

MESHLAB_PLUGIN_NAME_EXPORTER(IoAnimStreamPlugin)
