// SPDX-License-Identifier: GPL-3.0-or-later
// What the shared plugin bodies need from MeshLab, spelt once for every release we build for.
// ANIMC_MESHLAB_API (set by cmake/MeshLabPlugin.cmake from the SDK's layout) is
//   2020: MeshLab 2020.09 (Debian 12): public layer list, MeshModel::parent, RichSaveFile;
//   2022: MeshLab 2022.02: layers behind iterators and ids, parameters/ folder;
//   2023: MeshLab 2023.12 and 2025.07: as 2022, with the file parameters renamed.
// Only names and includes differ here; every signature that changed lives in the two plugin
// shells, which is where the interfaces really differ.
#pragma once
#include <QList>
#include <QString>

#if !defined(ANIMC_MESHLAB_API)
#error "ANIMC_MESHLAB_API must be 2020, 2022 or 2023 (set by cmake/MeshLabPlugin.cmake)"
#endif

#if ANIMC_MESHLAB_API == 2020
#include <common/filter_parameter/rich_parameter_list.h>
#include <common/meshmodel.h>
#else
#include <common/ml_document/mesh_document.h>
#include <common/parameters/rich_parameter_list.h>
#endif

namespace animc::meshlab::compat {

#if ANIMC_MESHLAB_API == 2023
using RichOpenFile = ::RichFileOpen;
using RichSaveFile = ::RichFileSave;
#else
using RichOpenFile = ::RichOpenFile;
using RichSaveFile = ::RichSaveFile;
#endif

// Every layer of the document, in document order.
inline QList<MeshModel*> layers(const MeshDocument& md) {
#if ANIMC_MESHLAB_API == 2020
  return md.meshList;
#else
  QList<MeshModel*> all;
  // The 2022+ document hands out const layers from a const document; the filters change them.
  for (const MeshModel& m : md.meshIterator()) all << const_cast<MeshModel*>(&m);
  return all;
#endif
}

inline void removeLayer(MeshDocument& md, MeshModel* m) {
#if ANIMC_MESHLAB_API == 2020
  md.delMesh(m);
#else
  md.delMesh(m->id());
#endif
}

inline void updateBoxAndNormals(MeshModel& m) {
#if ANIMC_MESHLAB_API == 2020
  m.UpdateBoxAndNormals();
#else
  m.updateBoxAndNormals();
#endif
}

inline void clearLayer(MeshModel& m) {
#if ANIMC_MESHLAB_API == 2020
  m.Clear();
#else
  m.clear();
#endif
}

// Adds a "choose a layer" parameter whose default is `layer` (null: none).
inline void addMeshParameter(RichParameterList& par, const QString& name, MeshModel* layer, const MeshDocument& md,
                             const QString& label, const QString& tooltip) {
#if ANIMC_MESHLAB_API == 2020
  par.addParam(RichMesh(name, layer, const_cast<MeshDocument*>(&md), label, tooltip));
#else
  par.addParam(RichMesh(name, layer != nullptr ? unsigned(layer->id()) : 0u, &md, label, tooltip));
#endif
}

// The layer a meshParameter names, or null.
inline MeshModel* meshValue(const RichParameterList& par, const QString& name, MeshDocument& md) {
#if ANIMC_MESHLAB_API == 2020
  (void)md;
  return par.getMesh(name);
#else
  return md.getMesh(par.getMeshId(name));
#endif
}

}  // namespace animc::meshlab::compat
