// SPDX-License-Identifier: GPL-3.0-or-later
// MeshLab 2020.09's GUI sets up rendering only for the layer an IO plugin's open() was given;
// other layers open() adds stay invisible until the user picks a render mode by hand.
#pragma once
#include <QList>
#include <common/meshmodel.h>

namespace animc::meshlab {

// In the GUI, gives `layers` the rendering the GUI gives a freshly opened mesh, in every view
// of md. Does nothing in meshlabserver (it has no views).
void setUpRenderingOfAddedLayers(MeshDocument& md, const QList<MeshModel*>& layers);

}  // namespace animc::meshlab
