// SPDX-License-Identifier: GPL-3.0-or-later
// The .ams IO plugin for MeshLab 2022.02, 2023.12 and 2025.07. Opening makes one layer per frame
// of the chosen range: MeshLab asks how many (numberMeshesContainedInFile), makes the layers and
// sets up their rendering, then open() decodes into them. Saving all layers needs the document,
// which only a project save gets: .ams is offered as a project format (File > Save Project,
// PyMeshLab's save_project), with the encoder's defaults; the filter offers every setting.
#pragma once
#include <common/plugins/interfaces/io_plugin.h>

class IoAnimStreamPlugin : public QObject, public IOPlugin {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(IO_PLUGIN_IID)
  Q_INTERFACES(IOPlugin)

 public:
  QString pluginName() const override { return "IOAnimStream"; }
  QString vendor() const override;
  std::list<FileFormat> importFormats() const override;
  std::list<FileFormat> exportFormats() const override;
  std::list<FileFormat> exportProjectFormats() const override;
  void exportMaskCapability(const QString& format, int& capability, int& defaultBits) const override;
  RichParameterList initPreOpenParameter(const QString& format) const override;

  unsigned int numberMeshesContainedInFile(const QString& format, const QString& fileName,
                                           const RichParameterList& par) const override;
  void open(const QString& format, const QString& fileName, const std::list<MeshModel*>& layers,
            std::list<int>& masks, const RichParameterList& par, vcg::CallBackPos* cb = nullptr) override;
  void open(const QString& format, const QString& fileName, MeshModel& m, int& mask, const RichParameterList& par,
            vcg::CallBackPos* cb = nullptr) override;
  void save(const QString& format, const QString& fileName, MeshModel& m, const int mask,
            const RichParameterList& par, vcg::CallBackPos* cb = nullptr) override;
  void saveProject(const QString& format, const QString& fileName, const MeshDocument& md, bool onlyVisibleMeshes,
                   const std::vector<MLRenderingData>& rendOpt, vcg::CallBackPos* cb = nullptr) override;

 private:
  void openLayers(const QString& fileName, const QList<MeshModel*>& layers, const RichParameterList& par,
                  vcg::CallBackPos* cb);
};
