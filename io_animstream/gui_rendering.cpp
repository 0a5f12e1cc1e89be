// SPDX-License-Identifier: GPL-3.0-or-later
#include "gui_rendering.h"

#include <QApplication>
#include <QGLWidget>
#include <common/ml_shared_data_context.h>

namespace animc::meshlab {
namespace {

// The default of MeshLab's "Default Face number per smooth rendering" setting, which the GUI
// applies to the layer it opened itself: below it a mesh is shaded per face. (The setting's
// value lives in the GUI's main window, out of a plugin's reach.)
constexpr size_t kMinFacesForSmoothShading = 50000;

// The document's shared GL context; the GUI creates it without a parent, so it is found among
// the application's widgets rather than as a child of the main window.
MLSceneGLSharedDataContext* sharedContextOf(MeshDocument& md) {
  for (QWidget* w : QApplication::allWidgets()) {
    auto* shared = qobject_cast<MLSceneGLSharedDataContext*>(w);
    if (shared != nullptr && &shared->meshDoc() == &md) return shared;
  }
  return nullptr;
}

// The 3D views: GLArea lives in the meshlab binary, not in libmeshlab-common, hence the name.
QList<QGLContext*> viewContexts() {
  QList<QGLContext*> views;
  for (QWidget* w : QApplication::allWidgets())
    if (qstrcmp(w->metaObject()->className(), "GLArea") == 0)
      views << const_cast<QGLContext*>(static_cast<QGLWidget*>(w)->context());
  return views;
}

}  // namespace

void setUpRenderingOfAddedLayers(MeshDocument& md, const QList<MeshModel*>& layers) {
  if (qobject_cast<QApplication*>(QCoreApplication::instance()) == nullptr) return;
  MLSceneGLSharedDataContext* shared = sharedContextOf(md);
  if (shared == nullptr) return;
  for (QGLContext* view : viewContexts()) {
    for (MeshModel* layer : layers) {
      MLRenderingData data;
      MLPoliciesStandAloneFunctions::suggestedDefaultPerViewRenderingData(layer, data, kMinFacesForSmoothShading);
      shared->setRenderingDataPerMeshView(layer->id(), view, data);
    }
  }
  for (MeshModel* layer : layers) shared->manageBuffers(layer->id());
}

}  // namespace animc::meshlab
