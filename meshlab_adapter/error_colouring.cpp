// SPDX-License-Identifier: GPL-3.0-or-later
#include "error_colouring.h"

#include <vcg/complex/algorithms/update/color.h>

namespace animc::meshlab {

void storeQuality(MeshModel& target, const std::vector<Scalarm>& errors) {
  target.updateDataMask(MeshModel::MM_VERTQUALITY);
  size_t i = 0;
  for (CVertexO& v : target.cm.vert)
    if (!v.IsD()) v.Q() = errors[i++];
}

void colourByQuality(MeshModel& layer, float scale_max) {
  layer.updateDataMask(MeshModel::MM_VERTCOLOR);
  // vcg's ramp runs red -> blue from its first bound to its second: give it (max, 0).
  const float top = scale_max > 0 ? scale_max : 1.0f;
  vcg::tri::UpdateColor<CMeshO>::PerVertexQualityRamp(layer.cm, top, 0.0f);
}

}  // namespace animc::meshlab
