// SPDX-License-Identifier: GPL-3.0-or-later
// mlxrun: runs MeshLab .mlx filter scripts headless on MeshLab 2022+ (which has no
// meshlabserver), with meshlabserver's flags, on libmeshlab-common alone: no window, no X
// server, no GL. It loads io_base and our plugins, opens the inputs, applies the script, saves
// the outputs and prints the log. A failing step exits with status 1 and its message, never
// with a signal.
#include <QApplication>
#include <QCoreApplication>
#include <QDir>
#include <cstdio>
#include <cstdlib>

#include <common/mlexception.h>

#include "runner.h"

namespace {

// MeshLab's debug chatter (it echoes every log entry as it is made, and reports its script
// parsing) is dropped: flushLog prints the log once, on stdout. Warnings stay on stderr.
void quietDebugOutput(QtMsgType type, const QMessageLogContext&, const QString& message) {
  if (type == QtDebugMsg || type == QtInfoMsg) return;
  std::fprintf(stderr, "%s\n", qUtf8Printable(message));
}

// $MLXRUN_PLUGIN_PATH, else the installed layout beside the binary.
QStringList pluginFolders() {
  const QString path = qEnvironmentVariable("MLXRUN_PLUGIN_PATH");
  if (!path.isEmpty()) return path.split(':', Qt::SkipEmptyParts);
  return {QDir(QCoreApplication::applicationDirPath()).filePath("../lib/meshlab/plugins")};
}

int run(const mlxrun::Options& options) {
  MeshDocument md;
  try {
    mlxrun::loadPlugins(pluginFolders());
    if (!options.dump_file.isEmpty()) mlxrun::dumpFilters(options.dump_file);
    mlxrun::openInputs(options.inputs, md);
    mlxrun::flushLog(md, options.log_file);
    if (!options.script.isEmpty()) mlxrun::runScript(options.script, md);
    mlxrun::flushLog(md, options.log_file);
    mlxrun::saveOutputs(options.outputs, md);
    mlxrun::flushLog(md, options.log_file);
    return 0;
  } catch (const std::exception& e) {
    // MLException included; bad_alloc and the like get the same treatment: a message, status 1.
    mlxrun::flushLog(md, options.log_file);
    std::fprintf(stderr, "mlxrun: %s\n", e.what());
    return 1;
  } catch (...) {
    std::fprintf(stderr, "mlxrun: unexpected error\n");
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Qt's widgets need a platform; offscreen needs no X server.
  if (std::getenv("QT_QPA_PLATFORM") == nullptr) setenv("QT_QPA_PLATFORM", "offscreen", 1);
  QApplication app(argc, argv);
  qInstallMessageHandler(quietDebugOutput);
  mlxrun::Options options;
  QString why;
  if (!mlxrun::parseOptions(app.arguments().mid(1), options, why)) {
    std::fprintf(stderr, "mlxrun: %s\n%s", qUtf8Printable(why), mlxrun::kUsage);
    return 2;
  }
  return run(options);
}
