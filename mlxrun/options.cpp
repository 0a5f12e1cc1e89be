// SPDX-License-Identifier: GPL-3.0-or-later
#include "options.h"

namespace mlxrun {

const char* const kUsage =
    "usage: mlxrun [-i FILE...] [-s SCRIPT.mlx] [-o FILE [-l LAYER|x]]... [-l LOG] [-d DUMP]\n"
    "  -i FILE...   open each file as layers (an .ams file: one layer per frame)\n"
    "  -s SCRIPT    apply the script's filters in order (parameters it leaves out keep their defaults)\n"
    "  -o FILE      save the current layer (-l LAYER: that one, -l x: the last) as FILE; a project format\n"
    "               (.ams) saves every layer\n"
    "  -l LOG       also write the log to LOG\n"
    "  -d DUMP      write the loaded filters and their parameters to DUMP\n"
    "Plugins: MeshLab's io_base and ours, from $MLXRUN_PLUGIN_PATH (folders, ':'-separated) or\n"
    "BIN/../lib/meshlab/plugins. Exit status: 0 done, 1 a file or filter failed, 2 bad arguments.\n";

namespace {

// meshlabserver's layer after "-o FILE -l": a number, or x for the last layer; else kCurrentLayer
// (the -l is then the log file's).
int layerArgument(const QString& s) {
  if (s == "x") return kLastLayer;
  bool ok = false;
  const int n = s.toInt(&ok);
  return ok && n >= 0 ? n : kCurrentLayer;
}

}  // namespace

bool parseOptions(const QStringList& args, Options& o, QString& why) {
  for (int i = 0; i < args.size(); ++i) {
    const QString& flag = args[i];
    if (!QStringList{"-i", "-s", "-o", "-l", "-d"}.contains(flag)) {
      why = flag.startsWith('-') ? "unknown option " + flag : "unexpected argument " + flag;
      return false;
    }
    const bool has_value = i + 1 < args.size() && !args[i + 1].startsWith('-');
    if (!has_value) {
      why = flag + " needs a value";
      return false;
    }
    if (flag == "-i") {
      while (i + 1 < args.size() && !args[i + 1].startsWith('-')) o.inputs << args[++i];
    } else if (flag == "-s") {
      o.script = args[++i];
    } else if (flag == "-o") {
      o.outputs.push_back({args[++i], kCurrentLayer});
      // meshlabserver's "-o FILE -l N" picks the layer to save.
      if (i + 2 < args.size() && args[i + 1] == "-l" && layerArgument(args[i + 2]) != kCurrentLayer) {
        o.outputs.back().layer = layerArgument(args[i + 2]);
        i += 2;
      }
    } else if (flag == "-l") {
      o.log_file = args[++i];
    } else {  // -d
      o.dump_file = args[++i];
    }
  }
  return true;
}

}  // namespace mlxrun
