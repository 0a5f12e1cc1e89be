// SPDX-License-Identifier: GPL-3.0-or-later
#include "filter_animcompress.h"

#include "compress_layers.h"
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

QString FilterAnimCompressPlugin::filterName(FilterIDType id) const {
  switch (id) {
    case FP_COMPRESS: return "Compress Animation Layers";
    case FP_RECONSTRUCTION_ERROR: return "Animation Reconstruction Error";
    case FP_IMPORT: return "Import Compressed Animation";
  }
  return {};
}

namespace {

QString filterDescription(FilterAnimCompressPlugin::FilterIDType id) {
  switch (id) {
    case FilterAnimCompressPlugin::FP_COMPRESS:
      return "Compresses an animation whose frames are the layers of the document (same vertices "
             "and triangles in every layer, in document order) into an .ams file with the "
             "animcompress codec library, then logs its size, bits per vertex per frame, "
             "Karni-Gotsman error, PSNR and max error. Optionally adds the frames a decoder will "
             "reconstruct as new layers and colours them by per-vertex error.";
    case FilterAnimCompressPlugin::FP_RECONSTRUCTION_ERROR:
      return "Compares two runs of layers (original frames and reconstructed ones) frame by frame. "
             "Each reconstructed vertex gets its error as vertex quality and a colour from blue "
             "(exact) to red (the colour scale's maximum, the same for every frame). Logs the RMS "
             "and max error of each frame and the figures of the whole animation.";
    case FilterAnimCompressPlugin::FP_IMPORT:
      return "Decodes an animcompress .ams file (all frames or a range) into one new layer per "
             "frame, labelled frame_00000, frame_00001, ... by frame number.";
  }
  return {};
}

}  // namespace

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
      par.addParam(RichOpenFile("AmsFile", "", QStringList() << "*.ams", "Compressed animation",
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
