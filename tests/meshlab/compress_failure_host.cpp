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
#include <QCoreApplication>
#include <QFileInfo>
#include <QPluginLoader>
#include <cmath>
#include <cstdio>
#include <limits>

#include <common/GLLogStream.h>
#include <common/interfaces.h>

#include "layer_frames.h"
#include "seqio/sequence_io.h"

namespace {

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

QAction* compressAction(MeshFilterInterface& filter) {
  for (QAction* a : filter.actions())
    if (a->text() == "Compress Animation Layers") return a;
  return nullptr;
}

void printLayers(const MeshDocument& md) {
  std::printf("layers: %d\n", md.size());
  for (int i = 0; i < md.size(); ++i) {
    const MeshModel& m = *md.meshList[i];
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
  auto* filter = qobject_cast<MeshFilterInterface*>(loader.instance());
  if (filter == nullptr) return hostError("cannot load " + loader.errorString().toStdString());
  QAction* compress = compressAction(*filter);
  if (compress == nullptr) return hostError("the plugin has no Compress Animation Layers");

  MeshDocument md;
  for (int i = 3; i < argc; ++i) {
    const animc::Status s = addFrameLayer(md, argv[i]);
    if (!s.ok()) return hostError(s.message());
  }
  md.meshList.back()->cm.vert[0].P()[0] = std::numeric_limits<Scalarm>::quiet_NaN();

  RichParameterList par;
  filter->initParameterSet(compress, md, par);
  par.setValue("OutputFile", FileValue(argv[2]));
  par.setValue("AddReconstructed", BoolValue(false));
  par.setValue("ColourByError", BoolValue(true));
  GLLogStream log;
  filter->setLog(&log);
  const bool ok = filter->applyFilter(compress, md, par, nullptr);
  QStringList lines;
  log.print(lines);
  for (const QString& line : lines) std::printf("%s\n", qUtf8Printable(line));
  printLayers(md);
  return ok ? 1 : 0;
}
