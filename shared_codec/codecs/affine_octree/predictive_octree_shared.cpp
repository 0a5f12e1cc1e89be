// SPDX-License-Identifier: Apache-2.0
#include <cmath>

#include "codecs/affine_octree/cell_kernels.h"
#include "codecs/affine_octree/predictive_octree.h"

namespace animc {

double residualStep(double max_error) { return 2.0 * max_error / std::sqrt(3.0) * 0.999; }

void CellPoints::gather(const PFrameInput& in, const uint32_t* idx, size_t n) {
  const size_t size = kPointStride * n;
  // Each as large as the largest cell gathered: the root's, every vertex. The target only
  // when encoding, the scratch only for the portable kernel (the AVX2 one keeps no copy of
  // frame f-2's points).
  if (reference.size() < size) reference.resize(size);
  if (in.target && target.size() < size) target.resize(size);
  if (!useAvx2(path) && scratch.size() < size) scratch.resize(size);
  if (in.before) {
    gatherWithMotion(path, in.reference->data(), in.before->data(), in.cube, idx, n, reference.data(), scratch.data(),
                     model.frame, model.prior);
  } else {
    model.frame = gatherPoints(path, in.reference->data(), idx, n, reference.data());
    model.prior = CentredAffine();
  }
  if (in.target) copyPoints(path, in.target->data(), idx, n, target.data());
}

}  // namespace animc
