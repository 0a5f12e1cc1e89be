// SPDX-License-Identifier: GPL-3.0-or-later
// The MeshLab filter plugin: declares the three animation filters and hands each to its
// function (compress_layers, reconstruction_error, layer_frames). No codec logic here.
#pragma once
#include <common/interfaces.h>

class FilterAnimCompressPlugin : public QObject, public MeshFilterInterface {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
  Q_INTERFACES(MeshFilterInterface)

 public:
  // The same ids as filter_texts.h's FilterId.
  enum { FP_COMPRESS, FP_RECONSTRUCTION_ERROR, FP_IMPORT };

  FilterAnimCompressPlugin();

  QString pluginName() const override;
  QString filterName(FilterIDType filter) const override;
  QString filterInfo(FilterIDType filter) const override;
  FilterClass getClass(QAction* a) override;
  FILTER_ARITY filterArity(QAction* a) const override;
  int getPreConditions(QAction* a) const override;
  int postCondition(QAction* a) const override;
  void initParameterSet(QAction* a, MeshDocument& md, RichParameterList& par) override;
  bool applyFilter(QAction* a, MeshDocument& md, const RichParameterList& par,
                   vcg::CallBackPos* cb) override;

 private:
  bool importAnimation(MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb);
  // Logs the failure (meshlabserver never prints errorMessage) and returns false.
  bool fail(QAction* a, const std::string& why);
};
