// SPDX-License-Identifier: GPL-3.0-or-later
// The filter plugin for MeshLab 2022.02, 2023.12 and 2025.07: the same three filters, names and
// parameters as the 2020.09 shell (so .mlx scripts keep working), declared through the 2022+
// interface. Failures are thrown as MLException, which MeshLab shows and PyMeshLab raises;
// Compress returns its figures, which PyMeshLab hands to the caller as a dict.
#pragma once
#include <common/plugins/interfaces/filter_plugin.h>

class FilterAnimCompressPlugin : public QObject, public FilterPlugin {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(FILTER_PLUGIN_IID)
  Q_INTERFACES(FilterPlugin)

 public:
  FilterAnimCompressPlugin();

  QString pluginName() const override;
  QString vendor() const override;
  QString filterName(ActionIDType filter) const override;
  QString filterInfo(ActionIDType filter) const override;
  FilterClass getClass(const QAction* a) const override;
  FilterArity filterArity(const QAction* a) const override;
  int getPreConditions(const QAction* a) const override;
  int postCondition(const QAction* a) const override;
  RichParameterList initParameterList(const QAction* a, const MeshDocument& md) override;
  std::map<std::string, QVariant> applyFilter(const QAction* a, const RichParameterList& par, MeshDocument& md,
                                              unsigned int& postConditionMask, vcg::CallBackPos* cb) override;

 private:
  std::map<std::string, QVariant> compress(const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb);
  std::map<std::string, QVariant> importAnimation(const RichParameterList& par, MeshDocument& md,
                                                  vcg::CallBackPos* cb);
};
