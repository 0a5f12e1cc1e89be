// SPDX-License-Identifier: GPL-3.0-or-later
// A minimal MeshLab host for what meshlabserver cannot show: the layers after a filter failed
// (meshlabserver exits as soon as a filter fails, before it saves anything). It loads the
// filter plugin, makes one layer per frame file, puts a NaN into the last layer so the encoder
// fails there, after every earlier frame went through its observer, and runs "Compress
// Animation Layers" colouring the originals (AddReconstructed off, ColourByError on).
//   usage: compress_failure_host PLUGIN.so OUT.ams FRAME.ply...
// Prints the filter's log, then "layers: N" and one line per layer:
//   "layer 3 'frame_0003.ply': quality no, colour no, non-zero quality 0"
// Exit status: 0 when the filter failed, 1 when it succeeded, 2 when the host could not run it.
// Built for every MeshLab interface (mlxrun, like meshlabserver, exits on a failed filter).
#include <QCoreApplication>
#include <QFileInfo>
#include <QPluginLoader>
#include <cmath>
#include <cstdio>
#include <limits>

#include <common/GLLogStream.h>

#include "layer_frames.h"
#include "meshlab_compat.h"
#include "seqio/sequence_io.h"

#if ANIMC_MESHLAB_API == 2020
#include <common/interfaces.h>
using FilterPlugin = MeshFilterInterface;
using FileParameterValue = FileValue;
#else
#include <common/plugins/interfaces/filter_plugin.h>
using FileParameterValue = StringValue;
#endif

namespace {

namespace compat = animc::meshlab::compat;

int hostError(const std::string& why) {
  std::fprintf(stderr, "compress_failure_host: %s\n", why.c_str());
  return 2;
}

// The file's one frame as a new layer labelled with the file's name.
animc::Status addFrameLayer(MeshDocument& md, const std::string& path) {
  ANIMC_ASSIGN_OR_RETURN(animc::Mesh mesh, animc::readMesh(path));
  MeshModel* layer = md.addNewMesh("", QFileInfo(QString::fromStdString(path)).fileName(), false);
  animc::meshlab::fillMesh(*layer, mesh.topology, mesh.positions.data());
  return animc::Status();
}

QAction* compressAction(FilterPlugin& filter) {
  for (QAction* a : filter.actions())
    if (a->text() == "Compress Animation Layers") return a;
  return nullptr;
}

// Runs the filter; false when it failed (2022+ throws, whose message goes to "failed: ...").
bool apply(FilterPlugin& filter, QAction* action, MeshDocument& md, const RichParameterList& par) {
#if ANIMC_MESHLAB_API == 2020
  return filter.applyFilter(action, md, par, nullptr);
#else
  try {
    unsigned int post_conditions = filter.postCondition(action);
    filter.applyFilter(action, par, md, post_conditions, nullptr);
    return true;
  } catch (const MLException& e) {
    std::printf("failed: %s\n", e.what());
    return false;
  }
#endif
}

void printLayers(const MeshDocument& md) {
  const QList<MeshModel*> layers = compat::layers(md);
  std::printf("layers: %d\n", int(layers.size()));
  for (int i = 0; i < layers.size(); ++i) {
    const MeshModel& m = *layers[i];
    int non_zero = 0;
    for (const CVertexO& v : m.cm.vert) non_zero += !v.IsD() && v.cQ() != 0;
    std::printf("layer %d '%s': quality %s, colour %s, non-zero quality %d\n", i, qUtf8Printable(m.label()),
                m.hasDataMask(MeshModel::MM_VERTQUALITY) ? "yes" : "no",
                m.hasDataMask(MeshModel::MM_VERTCOLOR) ? "yes" : "no", non_zero);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) return hostError("usage: compress_failure_host PLUGIN.so OUT.ams FRAME.ply FRAME.ply...");
  QCoreApplication app(argc, argv);
  QPluginLoader loader(argv[1]);
  auto* filter = qobject_cast<FilterPlugin*>(loader.instance());
  if (filter == nullptr) return hostError("cannot load " + loader.errorString().toStdString());
  QAction* compress = compressAction(*filter);
  if (compress == nullptr) return hostError("the plugin has no Compress Animation Layers");

  MeshDocument md;
  for (int i = 3; i < argc; ++i) {
    const animc::Status s = addFrameLayer(md, argv[i]);
    if (!s.ok()) return hostError(s.message());
  }
  compat::layers(md).back()->cm.vert[0].P()[0] = std::numeric_limits<Scalarm>::quiet_NaN();

#if ANIMC_MESHLAB_API == 2020
  RichParameterList par;
  filter->initParameterSet(compress, md, par);
#else
  RichParameterList par = filter->initParameterList(compress, md);
#endif
  par.setValue("OutputFile", FileParameterValue(argv[2]));
  par.setValue("AddReconstructed", BoolValue(false));
  par.setValue("ColourByError", BoolValue(true));
  GLLogStream log;
  filter->setLog(&log);
  const bool ok = apply(*filter, compress, md, par);
  QStringList lines;
  log.print(lines);
  for (const QString& line : lines) std::printf("%s\n", qUtf8Printable(line));
  printLayers(md);
  return ok ? 1 : 0;
}
