// SPDX-License-Identifier: Apache-2.0
#include <cmath>

#include "codecs/affine_octree/cell_kernels.h"
#include "codecs/affine_octree/predictive_octree.h"
#include "core/large_memory.h"

namespace animc {

double residualStep(double max_error) { return 2.0 * max_error / std::sqrt(3.0) * 0.999; }

CellPoints::CellPoints(CellPoints& whole, size_t first)
    : path(whole.path), reference_(whole.reference_ + kPointStride * first),
      target_(whole.target_ ? whole.target_ + kPointStride * first : nullptr),
      scratch_(whole.scratch_ ? whole.scratch_ + kPointStride * first : nullptr), window_(true) {}

void CellPoints::gather(const PFrameInput& in, const uint32_t* idx, size_t n) {
  if (!window_) {
    const size_t size = kPointStride * n;
    auto grow = [size](std::vector<double>& buffer) {
      if (buffer.size() < size) resizeWithHugePages(buffer, size);
    };
    grow(own_reference_);
    if (in.target) grow(own_target_);
    if (!useAvx2(path)) grow(own_scratch_);
    reference_ = own_reference_.data();
    target_ = own_target_.data();
    scratch_ = own_scratch_.data();
  }
  if (in.before) {
    gatherWithMotion(path, in.reference->data(), in.before->data(), in.cube, idx, n, reference_, scratch_, model.frame,
                     model.prior);
  } else {
    model.frame = gatherPoints(path, in.reference->data(), idx, n, reference_);
    model.prior = CentredAffine();
  }
  if (in.target) copyPoints(path, in.target->data(), idx, n, target_);
}

}  // namespace animc
