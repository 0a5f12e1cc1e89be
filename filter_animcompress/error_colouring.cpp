#include "error_colouring.h"

#include <cmath>

#include <vcg/complex/algorithms/update/color.h>

namespace animc::meshlab {

void storeVertexError(MeshModel& target, const float* original, const float* reconstructed) {
  target.updateDataMask(MeshModel::MM_VERTQUALITY);
  size_t i = 0;
  for (CVertexO& v : target.cm.vert) {
    if (v.IsD()) continue;
    const double dx = double(reconstructed[i]) - original[i];
    const double dy = double(reconstructed[i + 1]) - original[i + 1];
    const double dz = double(reconstructed[i + 2]) - original[i + 2];
    v.Q() = Scalarm(std::sqrt(dx * dx + dy * dy + dz * dz));
    i += 3;
  }
}

void colourByQuality(MeshModel& layer, float scale_max) {
  layer.updateDataMask(MeshModel::MM_VERTCOLOR);
  // vcg's ramp runs red -> blue from its first bound to its second: give it (max, 0).
  const float top = scale_max > 0 ? scale_max : 1.0f;
  vcg::tri::UpdateColor<CMeshO>::PerVertexQualityRamp(layer.cm, top, 0.0f);
}

}  // namespace animc::meshlab
