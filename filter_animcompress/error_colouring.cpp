// SPDX-License-Identifier: GPL-3.0-or-later
#include "error_colouring.h"

#include <cmath>

#include <vcg/complex/algorithms/update/color.h>

namespace animc::meshlab {

std::vector<Scalarm> vertexErrors(const float* original, const float* reconstructed, uint32_t vertex_count) {
  std::vector<Scalarm> errors(vertex_count);
  for (size_t v = 0, i = 0; v < vertex_count; ++v, i += 3) {
    const double dx = double(reconstructed[i]) - original[i];
    const double dy = double(reconstructed[i + 1]) - original[i + 1];
    const double dz = double(reconstructed[i + 2]) - original[i + 2];
    errors[v] = Scalarm(std::sqrt(dx * dx + dy * dy + dz * dz));
  }
  return errors;
}

void storeQuality(MeshModel& target, const std::vector<Scalarm>& errors) {
  target.updateDataMask(MeshModel::MM_VERTQUALITY);
  size_t i = 0;
  for (CVertexO& v : target.cm.vert)
    if (!v.IsD()) v.Q() = errors[i++];
}

void storeVertexError(MeshModel& target, const float* original, const float* reconstructed) {
  storeQuality(target, vertexErrors(original, reconstructed, uint32_t(target.cm.vn)));
}

void colourByQuality(MeshModel& layer, float scale_max) {
  layer.updateDataMask(MeshModel::MM_VERTCOLOR);
  // vcg's ramp runs red -> blue from its first bound to its second: give it (max, 0).
  const float top = scale_max > 0 ? scale_max : 1.0f;
  vcg::tri::UpdateColor<CMeshO>::PerVertexQualityRamp(layer.cm, top, 0.0f);
}

}  // namespace animc::meshlab
