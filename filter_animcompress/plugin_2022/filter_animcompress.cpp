// SPDX-License-Identifier: GPL-3.0-or-later
#include "filter_animcompress.h"

#include <common/mlexception.h>

#include "animc/animc.h"
#include "compress_layers.h"
#include "filter_texts.h"
#include "frame_range_parameters.h"
#include "layer_frames.h"
#include "reconstruction_error.h"

using namespace animc::meshlab;

namespace {

// A shared body's failure (a non-empty reason) as MeshLab 2022+ expects it.
void throwIfFailed(const std::string& why) {
  if (!why.empty()) throw MLException(QString::fromStdString(why));
}

}  // namespace

FilterAnimCompressPlugin::FilterAnimCompressPlugin() {
  typeList = {kCompressFilter, kReconstructionErrorFilter, kImportFilter};
  for (ActionIDType id : typeList) actionList.push_back(new QAction(filterName(id), this));
}

QString FilterAnimCompressPlugin::pluginName() const { return "FilterAnimCompress"; }

QString FilterAnimCompressPlugin::vendor() const { return "animcompress " ANIMC_VERSION_STRING; }

QString FilterAnimCompressPlugin::filterName(ActionIDType id) const { return filterTitle(int(id)); }

QString FilterAnimCompressPlugin::filterInfo(ActionIDType id) const {
  return filterDescription(int(id)) + " (animcompress " ANIMC_VERSION_STRING ")";
}

FilterPlugin::FilterClass FilterAnimCompressPlugin::getClass(const QAction* a) const {
  switch (ID(a)) {
    case kCompressFilter: return FilterPlugin::Layer;
    case kReconstructionErrorFilter: return FilterClass(FilterPlugin::Measure | FilterPlugin::VertexColoring);
    case kImportFilter: return FilterPlugin::MeshCreation;
  }
  return FilterPlugin::Layer;  // never Generic: PluginManager refuses it
}

FilterPlugin::FilterArity FilterAnimCompressPlugin::filterArity(const QAction* a) const {
  return ID(a) == kImportFilter ? NONE : VARIABLE;
}

int FilterAnimCompressPlugin::getPreConditions(const QAction*) const { return MeshModel::MM_NONE; }

int FilterAnimCompressPlugin::postCondition(const QAction* a) const {
  return ID(a) == kImportFilter ? int(MeshModel::MM_NONE) : int(MeshModel::MM_VERTCOLOR | MeshModel::MM_VERTQUALITY);
}

RichParameterList FilterAnimCompressPlugin::initParameterList(const QAction* a, const MeshDocument& md) {
  RichParameterList par;
  switch (ID(a)) {
    case kCompressFilter: addCompressParameters(md, par); break;
    case kReconstructionErrorFilter: addErrorParameters(md, par); break;
    case kImportFilter:
      par.addParam(compat::RichOpenFile("AmsFile", "", QStringList() << "*.ams", "Compressed animation",
                                        "The .ams file to decode."));
      addFrameRangeParameters(par);
      break;
  }
  return par;
}

std::map<std::string, QVariant> FilterAnimCompressPlugin::applyFilter(const QAction* a, const RichParameterList& par,
                                                                      MeshDocument& md, unsigned int&,
                                                                      vcg::CallBackPos* cb) {
  try {
    switch (ID(a)) {
      case kCompressFilter: return compress(par, md, cb);
      case kReconstructionErrorFilter: {
        const LogFn log = [this](const std::string& line) { this->log(line); };
        throwIfFailed(measureReconstructionError(md, par, cb, log));
        return {};
      }
      case kImportFilter: return importAnimation(par, md, cb);
    }
  } catch (const MLException&) {
    throw;
  } catch (...) {
    // bad_alloc and the like become a message, as in the 2020.09 shell.
    throw MLException(QString::fromStdString(currentExceptionMessage()));
  }
  wrongActionCalled(a);
  return {};
}

std::map<std::string, QVariant> FilterAnimCompressPlugin::compress(const RichParameterList& par, MeshDocument& md,
                                                                   vcg::CallBackPos* cb) {
  const LogFn log = [this](const std::string& line) { this->log(line); };
  CompressFigures f;
  throwIfFailed(compressLayers(md, par, cb, log, &f));
  return {{"ratio", f.ratio},         {"bpvf", f.bpvf},           {"kg_error", f.kg_error},
          {"psnr", f.psnr},           {"max_error", f.max_error}, {"bytes", QVariant::fromValue<qulonglong>(f.bytes)}};
}

std::map<std::string, QVariant> FilterAnimCompressPlugin::importAnimation(const RichParameterList& par,
                                                                          MeshDocument& md, vcg::CallBackPos* cb) {
  const std::string path = par.getOpenFileName("AmsFile").toStdString();
  if (path.empty()) throw MLException("no .ams file given");
  auto layers = importAms(path, frameRangeFrom(par), &md, nullptr, progressFrom(cb));
  if (!layers.ok()) throw MLException(QString::fromStdString(layers.status().message()));
  md.setCurrentMesh(layers.value()[0]->id());
  log("Imported %d frames of %d vertices from %s", int(layers.value().size()), layers.value()[0]->cm.vn,
      path.c_str());
  return {{"frames", int(layers.value().size())}};
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterAnimCompressPlugin)
