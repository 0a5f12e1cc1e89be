// SPDX-License-Identifier: GPL-3.0-or-later
#include "filter_animcompress.h"

#include "compress_layers.h"
#include "filter_texts.h"
#include "frame_range_parameters.h"
#include "layer_frames.h"
#include "reconstruction_error.h"
#include "animc/animc.h"

using namespace animc::meshlab;

FilterAnimCompressPlugin::FilterAnimCompressPlugin() {
  typeList << FP_COMPRESS << FP_RECONSTRUCTION_ERROR << FP_IMPORT;
  for (FilterIDType id : types()) actionList << new QAction(filterName(id), this);
}

QString FilterAnimCompressPlugin::pluginName() const { return "FilterAnimCompress"; }

// The enum's order is filter_texts.h's.
QString FilterAnimCompressPlugin::filterName(FilterIDType id) const { return filterTitle(id); }

// MeshLab 2020.09's plugin info has no version field: the release goes in every description.
QString FilterAnimCompressPlugin::filterInfo(FilterIDType id) const {
  return filterDescription(id) + " (animcompress " ANIMC_VERSION_STRING ")";
}

MeshFilterInterface::FilterClass FilterAnimCompressPlugin::getClass(QAction* a) {
  switch (ID(a)) {
    case FP_COMPRESS: return MeshFilterInterface::Layer;
    case FP_RECONSTRUCTION_ERROR:
      return FilterClass(MeshFilterInterface::Measure | MeshFilterInterface::VertexColoring);
    case FP_IMPORT: return MeshFilterInterface::MeshCreation;
  }
  return MeshFilterInterface::Layer;  // never Generic: PluginManager would abort on it
}

MeshFilterInterface::FILTER_ARITY FilterAnimCompressPlugin::filterArity(QAction* a) const {
  return ID(a) == FP_IMPORT ? NONE : VARIABLE;
}

int FilterAnimCompressPlugin::getPreConditions(QAction*) const { return MeshModel::MM_NONE; }

int FilterAnimCompressPlugin::postCondition(QAction* a) const {
  return ID(a) == FP_IMPORT ? int(MeshModel::MM_NONE)
                            : int(MeshModel::MM_VERTCOLOR | MeshModel::MM_VERTQUALITY);
}

void FilterAnimCompressPlugin::initParameterSet(QAction* a, MeshDocument& md, RichParameterList& par) {
  switch (ID(a)) {
    case FP_COMPRESS: addCompressParameters(md, par); break;
    case FP_RECONSTRUCTION_ERROR: addErrorParameters(md, par); break;
    case FP_IMPORT:
      par.addParam(compat::RichOpenFile("AmsFile", "", QStringList() << "*.ams", "Compressed animation",
                                        "The .ams file to decode."));
      addFrameRangeParameters(par);
      break;
  }
}

bool FilterAnimCompressPlugin::applyFilter(QAction* a, MeshDocument& md, const RichParameterList& par,
                                           vcg::CallBackPos* cb) {
  const LogFn log = [this](const std::string& line) { Log("%s", line.c_str()); };
  try {
    switch (ID(a)) {
      case FP_COMPRESS: {
        const std::string why = compressLayers(md, par, cb, log);
        return why.empty() || fail(a, why);
      }
      case FP_RECONSTRUCTION_ERROR: {
        const std::string why = measureReconstructionError(md, par, cb, log);
        return why.empty() || fail(a, why);
      }
      case FP_IMPORT: return importAnimation(md, par, cb);
    }
  } catch (...) {
    return fail(a, currentExceptionMessage());
  }
  return fail(a, "unknown filter");
}

bool FilterAnimCompressPlugin::importAnimation(MeshDocument& md, const RichParameterList& par,
                                               vcg::CallBackPos* cb) {
  const std::string path = par.getOpenFileName("AmsFile").toStdString();
  if (path.empty()) return fail(actionList[FP_IMPORT], "no .ams file given");
  auto layers = importAms(path, frameRangeFrom(par), &md, nullptr, progressFrom(cb));
  if (!layers.ok()) return fail(actionList[FP_IMPORT], layers.status().message());
  md.setCurrentMesh(layers.value()[0]->id());
  Log("Imported %d frames of %d vertices from %s", layers.value().size(), layers.value()[0]->cm.vn,
      path.c_str());
  return true;
}

bool FilterAnimCompressPlugin::fail(QAction* a, const std::string& why) {
  errorMessage = QString::fromStdString(why);
  Log("%s failed: %s", qUtf8Printable(a->text()), why.c_str());
  return false;
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterAnimCompressPlugin)
