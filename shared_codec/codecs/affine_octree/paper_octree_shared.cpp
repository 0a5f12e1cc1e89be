#include <algorithm>
#include <cmath>

#include "codecs/affine_octree/paper_octree.h"

namespace animc {

uint32_t quantizeUnit(double value, double lo, double hi, int bits) {
  const double levels = double((1u << bits) - 1);
  const double x = std::llround((value - lo) / (hi - lo) * levels);
  return uint32_t(std::clamp(x, 0.0, levels));
}

double dequantizeUnit(uint32_t q, double lo, double hi, int bits) {
  return lo + double(q) * (hi - lo) / double((1u << bits) - 1);
}

void applyAffine34(const double a[12], const double* u, double* out) {
  for (int r = 0; r < 3; ++r)
    out[r] = a[4 * r] * u[0] + a[4 * r + 1] * u[1] + a[4 * r + 2] * u[2] + a[4 * r + 3];
}

}  // namespace animc
