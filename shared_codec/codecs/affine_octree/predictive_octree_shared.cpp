#include <cmath>

#include "codecs/affine_octree/predictive_octree.h"

namespace animc {

double residualStep(double max_error) { return 2.0 * max_error / std::sqrt(3.0) * 0.999; }

LeafModel leafModel(const PFrameInput& in, const Cell& cell, const uint32_t* idx) {
  const size_t n = cell.end - cell.begin;
  LeafModel m;
  m.frame = cellFrame(*in.reference, idx, n);
  if (in.before) {
    // The cell's own motion from f-2 to f-1, assumed to continue.
    static const double kZero[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    const CellFrame before = cellFrame(*in.before, idx, n);
    fitCentred(*in.before, *in.reference, idx, n, before, kZero, m.prior);
  }
  return m;
}

CentredAffine codedAffine(const LeafModel& m, const int64_t coded[12], double step) {
  CentredAffine a = m.prior;
  const double st = step * kTranslationStep;
  const double sl = step * kLinearStep / m.frame.radius;
  for (int r = 0; r < 3; ++r) a.t[r] += double(coded[r]) * st;
  for (int k = 0; k < 9; ++k) a.L[k] += double(coded[3 + k]) * sl;
  return a;
}

}  // namespace animc
