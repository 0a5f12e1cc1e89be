// SPDX-License-Identifier: GPL-3.0-or-later
// The MeshLab IO plugin for .ams files: open decodes frames into layers, save encodes every
// layer as a frame. A thin adapter over shared_codec (through filter_animcompress's adapter).
#pragma once
#include <QObject>
#include <common/interfaces.h>

class IoAnimStreamPlugin : public QObject, public MeshIOInterface {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(MESH_IO_INTERFACE_IID)
  Q_INTERFACES(MeshIOInterface)

 public:
  QString pluginName() const override { return "IOAnimStream"; }
  QList<Format> importFormats() const override;
  QList<Format> exportFormats() const override;
  void GetExportMaskCapability(QString& format, int& capability, int& defaultBits) const override;
  void initPreOpenParameter(const QString& format, const QString& fileName, RichParameterList& par) override;
  void initSaveParameter(const QString& format, MeshModel& m, RichParameterList& par) override;

  bool open(const QString& format, const QString& fileName, MeshModel& m, int& mask,
            const RichParameterList& par, vcg::CallBackPos* cb = nullptr, QWidget* parent = nullptr) override;
  bool save(const QString& format, const QString& fileName, MeshModel& m, const int mask,
            const RichParameterList& par, vcg::CallBackPos* cb = nullptr, QWidget* parent = nullptr) override;

 private:
  // The bodies of open() and save(), which turn any exception these let out into a failure.
  bool openFrames(const QString& fileName, MeshModel& m, int& mask, const RichParameterList& par,
                  vcg::CallBackPos* cb);
  bool saveFrames(const QString& fileName, MeshModel& m, const RichParameterList& par, vcg::CallBackPos* cb);
  // Logs the failure (meshlabserver never prints errorMessage) and returns false.
  bool fail(const QString& what, const QString& fileName, const std::string& why);
};
