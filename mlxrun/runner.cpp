// SPDX-License-Identifier: GPL-3.0-or-later
#include "runner.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QTextStream>
#include <cstdio>

#include <common/filterscript.h>
#include <common/globals.h>
#include <common/mlexception.h>
#include <common/plugins/plugin_manager.h>
#include <common/utilities/load_save.h>

namespace mlxrun {
namespace {

// Progress goes nowhere: the log says what happened, and a batch run has no one watching.
bool quietProgress(const int, const char*) { return true; }

QAction* filterNamed(const QString& name) {
  QAction* action = meshlab::pluginManagerInstance().filterAction(name);
  if (action == nullptr) throw MLException("filter '" + name + "' not found (is its plugin loaded?)");
  return action;
}

// The filter's defaults, overridden by the script's values.
RichParameterList filterParameters(FilterPlugin& plugin, QAction* action, const RichParameterList& given,
                                   const MeshDocument& md) {
  RichParameterList par = plugin.initParameterList(action, md);
  for (const RichParameter& p : given) {
    if (!par.hasParameter(p.name()))
      throw MLException("filter '" + action->text() + "' has no parameter '" + p.name() + "'");
    par.setValue(p.name(), p.value());
  }
  return par;
}

}  // namespace

void loadPlugins(const QStringList& folders) {
  PluginManager& pm = meshlab::pluginManagerInstance();
  for (const QString& folder : folders) {
    const QDir dir(folder);
    for (const QString& name : dir.entryList({"*.so"}, QDir::Files, QDir::Name)) pm.loadPlugin(dir.filePath(name));
  }
  if (pm.size() == 0) throw MLException("no MeshLab plugins found in " + folders.join(", "));
}

void dumpFilters(const QString& path) {
  QFile file(path);
  if (!file.open(QIODevice::WriteOnly | QIODevice::Text)) throw MLException("cannot write " + path);
  QTextStream out(&file);
  MeshDocument md;  // parameters whose defaults depend on the document see an empty one
  for (FilterPlugin* plugin : meshlab::pluginManagerInstance().filterPluginIterator()) {
    int index = 0;  // per plugin
    for (QAction* action : plugin->actions()) {
      out << "\\section f" << index++ << " " << action->text() << "\n" << plugin->filterInfo(action) << "\n";
      for (const RichParameter& p : plugin->initParameterList(action, md))
        out << "  " << p.name() << " (" << p.stringType() << ") " << p.fieldDescription() << " -- " << p.toolTip()
            << "\n";
    }
  }
  std::printf("Dump file is saved in %s\n", qUtf8Printable(path));
}

void openInputs(const QStringList& inputs, MeshDocument& md) {
  for (const QString& input : inputs) {
    const QString path = QFileInfo(input).absoluteFilePath();
    for (MeshModel* m : meshlab::loadMeshWithStandardParameters(path, md, quietProgress))
      std::printf("Mesh %s loaded has %d vn %d fn\n", qUtf8Printable(m->label()), m->cm.vn, m->cm.fn);
  }
}

void runScript(const QString& script, MeshDocument& md) {
  FilterScript filters;
  if (!filters.open(script)) throw MLException("cannot read the filter script " + script);
  PluginManager& pm = meshlab::pluginManagerInstance();
  for (const FilterNameParameterValuesPair& step : filters) {
    QAction* action = filterNamed(step.filterName());
    FilterPlugin& plugin = *pm.getFilterPluginFromAction(action);
    const RichParameterList par = filterParameters(plugin, action, step.second, md);
    plugin.setLog(&md.Log);
    unsigned int post_condition = plugin.postCondition(action);
    try {
      plugin.applyFilter(action, par, md, post_condition, quietProgress);
    } catch (const MLException& e) {
      throw MLException(action->text() + " failed: " + e.what());
    }
    md.Log.logf(GLLogStream::SYSTEM, "Applied filter %s", qUtf8Printable(action->text()));
  }
}

void saveOutputs(const std::vector<Output>& outputs, MeshDocument& md) {
  PluginManager& pm = meshlab::pluginManagerInstance();
  for (const Output& o : outputs) {
    const QString path = QFileInfo(o.path).absoluteFilePath();
    const QString format = QFileInfo(path).suffix().toLower();
    if (!pm.isOutputMeshFormatSupported(format) && pm.isOutputProjectFormatSupported(format)) {
      meshlab::saveProject(path, md, false);  // .ams: every layer a frame
      continue;
    }
    MeshModel* layer = o.layer == kCurrentLayer ? md.mm() : nullptr;
    int position = 0;
    for (MeshModel& m : md.meshIterator())
      if (position++ == o.layer || o.layer == kLastLayer) layer = &m;
    if (layer == nullptr) throw MLException("no layer " + QString::number(o.layer) + " to save as " + path);
    meshlab::saveMeshWithStandardParameters(path, *layer, &md.Log);
    std::printf("Mesh %s saved as %s (%d vn %d fn)\n", qUtf8Printable(layer->label()), qUtf8Printable(path),
                layer->cm.vn, layer->cm.fn);
  }
}

void flushLog(MeshDocument& md, const QString& log_file) {
  static int printed = 0;
  const auto& entries = md.Log.logStringList();
  QFile file(log_file);
  const bool to_file = !log_file.isEmpty() && file.open(QIODevice::Append | QIODevice::Text);
  for (; printed < entries.size(); ++printed) {
    const QByteArray line = entries[printed].second.toUtf8();
    std::printf("LOG: %d %s\n", entries[printed].first, line.constData());
    if (to_file) file.write("LOG: " + QByteArray::number(entries[printed].first) + " " + line + "\n");
  }
  std::fflush(stdout);
}

}  // namespace mlxrun
