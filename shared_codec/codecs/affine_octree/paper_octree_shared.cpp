// SPDX-License-Identifier: Apache-2.0
#include <algorithm>
#include <cmath>

#include "codecs/affine_octree/paper_octree.h"

namespace animc {

uint32_t quantiseUnit(double value, double lo, double hi, int bits) {
  const double levels = double((1u << bits) - 1);
  const double x = std::llround((value - lo) / (hi - lo) * levels);
  return uint32_t(std::clamp(x, 0.0, levels));
}

}  // namespace animc
